//! Moving objects: their motion keys and when they are visible.

use super::*;

impl Cx<'_> {
    /// The `[shapes.motion]` table of shape `name`, if any.
    pub(super) fn shape_motion(
        &self,
        r: &RawShape,
        name: &str,
    ) -> Result<Option<Motion>, SceneError> {
        let Some(raw) = &r.motion else {
            return Ok(None);
        };
        let label = &format!("shape {name:?}: motion");
        let kind = r.kind.get_ref().as_str();
        if kind == "plane" {
            return Err(self.invalid(
                raw.span(),
                format!(
                    "shape {name:?}: a plane cannot move (it is infinite); use a quad for a \
                     moving floor or wall"
                ),
            ));
        }
        let m = raw.get_ref();
        let mut keys: Vec<MotionKey> = Vec::new();
        if let Some(list) = &m.keys {
            for (i, k) in list.get_ref().iter().enumerate() {
                let key_label = &format!("{label}: key {}", i + 1);
                let kr = k.get_ref();
                let t = self.seconds(key_label, "t", &kr.t)?;
                if let Some(prev) = keys.last()
                    && t <= prev.t
                {
                    return Err(self.invalid(
                        kr.t.span(),
                        format!(
                            "{key_label}: key times must increase, but t = {t} is not after \
                             key {i}'s t = {}",
                            prev.t
                        ),
                    ));
                }
                let scale = match &kr.scale {
                    Some(s) => {
                        let v = self.scale(key_label, s)?;
                        if kind == "sphere" && !(v.x == v.y && v.y == v.z) {
                            return Err(self.invalid(
                                s.span(),
                                format!(
                                    "{key_label}: a sphere stays a sphere, so its scale must be \
                                     one number, got {v}"
                                ),
                            ));
                        }
                        Some(v)
                    }
                    None => None,
                };
                keys.push(MotionKey {
                    t,
                    translate: match &kr.translate {
                        Some(v) => Some(self.vec3(key_label, "translate", v)?),
                        None => None,
                    },
                    rotate_y_deg: match &kr.rotate_y_deg {
                        Some(a) => Some(self.number(key_label, "rotate_y_deg", a)?),
                        None => None,
                    },
                    scale,
                });
            }
            if keys.is_empty() {
                return Err(self.invalid(
                    list.span(),
                    format!("{label}: keys must list at least one key"),
                ));
            }
        }
        let looped = m.looped.as_ref().is_some_and(|l| *l.get_ref());
        if looped {
            let span = m.looped.as_ref().map_or(raw.span(), |l| l.span());
            let (Some(first), Some(last)) = (keys.first(), keys.last()) else {
                return Err(self.invalid(span, format!("{label}: loop needs keys to repeat")));
            };
            if keys.len() < 2
                || (first.translate, first.rotate_y_deg, first.scale)
                    != (last.translate, last.rotate_y_deg, last.scale)
            {
                return Err(self.invalid(
                    span,
                    format!(
                        "{label}: a looped motion's last key closes the lap, so it must repeat \
                         the first key's translate, rotate_y_deg and scale (at a later t)"
                    ),
                ));
            }
        }
        let spin_deg_per_s = match &m.spin_deg_per_s {
            Some(s) => self.number(label, "spin_deg_per_s", s)?,
            None => 0.0,
        };
        let visible = match &m.visible {
            Some(list) => Some(self.visible(list, label)?),
            None => None,
        };
        Ok(Some(Motion {
            keys,
            looped,
            spin_deg_per_s,
            visible,
        }))
    }

    /// Visibility intervals: at least one, each [start, end) not empty, in increasing order
    /// without overlaps.
    pub(super) fn visible(
        &self,
        list: &Spanned<Vec<Spanned<[f64; 2]>>>,
        label: &str,
    ) -> Result<Vec<[f64; 2]>, SceneError> {
        if list.get_ref().is_empty() {
            return Err(self.invalid(
                list.span(),
                format!(
                    "{label}: visible must list at least one [start, end] interval (leave it \
                     out for always)"
                ),
            ));
        }
        let mut spans: Vec<[f64; 2]> = Vec::new();
        for (i, v) in list.get_ref().iter().enumerate() {
            let [start, end] = *v.get_ref();
            let which = format!("{label}: visible interval {}", i + 1);
            if !(start.is_finite() && end.is_finite()) {
                return Err(self.invalid(
                    v.span(),
                    format!("{which} [{start}, {end}] must be finite numbers of seconds"),
                ));
            }
            if end <= start {
                return Err(self.invalid(
                    v.span(),
                    format!("{which} [{start}, {end}] is empty: its end must be after its start"),
                ));
            }
            if let Some(&[p_start, p_end]) = spans.last()
                && start < p_end
            {
                return Err(self.invalid(
                    v.span(),
                    format!(
                        "{which} [{start}, {end}] overlaps or precedes interval {i} \
                         [{p_start}, {p_end}]: list the intervals in time order, apart"
                    ),
                ));
            }
            spans.push([start, end]);
        }
        Ok(spans)
    }
}
