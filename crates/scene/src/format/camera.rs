//! The scene's camera and camera paths (a sweep, pans or keys).

use super::*;

impl Cx<'_> {
    pub(super) fn camera(&self, raw: &Spanned<RawCamera>) -> Result<Camera, SceneError> {
        let r = raw.get_ref();
        let label = "camera";
        let eye = self.vec3(label, "eye", &r.eye)?;
        let up = match &r.up {
            Some(u) => self.nonzero(label, "up", u)?,
            None => Vec3::Y,
        };
        let vfov_deg = match &r.vfov_deg {
            Some(v) => self.field_of_view(label, v)?,
            None => DEFAULT_VFOV_DEG,
        };
        if r.pitch_deg.is_some() && r.yaw_deg.is_none() {
            let span = r.pitch_deg.as_ref().map_or(raw.span(), |p| p.span());
            return Err(self.invalid(span, "camera: pitch_deg needs yaw_deg".to_owned()));
        }
        let given = [
            r.target.as_ref().map(|t| ("target", t.span())),
            r.forward.as_ref().map(|f| ("forward", f.span())),
            r.yaw_deg.as_ref().map(|y| ("yaw_deg", y.span())),
        ];
        let mut given: Vec<_> = given.into_iter().flatten().collect();
        given.sort_by_key(|g| g.1.start);
        if given.len() != 1 {
            let span = given.get(1).map_or(raw.span(), |g| g.1.clone());
            return Err(self.invalid(
                span,
                format!(
                    "camera: give exactly one of `target`, `forward` or `yaw_deg` (got {})",
                    if given.is_empty() {
                        "none".to_owned()
                    } else {
                        given.iter().map(|g| g.0).collect::<Vec<_>>().join(", ")
                    }
                ),
            ));
        }
        let camera = if let Some(t) = &r.target {
            let target = self.vec3(label, "target", t)?;
            if target == eye {
                return Err(
                    self.invalid(t.span(), "camera: target must differ from eye".to_owned())
                );
            }
            Camera::look_at(eye, target, up, vfov_deg)
        } else if let Some(f) = &r.forward {
            Camera {
                eye,
                forward: unit(self.nonzero(label, "forward", f)?),
                up,
                vfov_deg,
            }
        } else {
            let yaw = r
                .yaw_deg
                .as_ref()
                .map_or(Ok(0.0), |y| self.number(label, "yaw_deg", y))?;
            let pitch = r
                .pitch_deg
                .as_ref()
                .map_or(Ok(0.0), |p| self.number(label, "pitch_deg", p))?;
            yaw_pitch_deg_camera(eye, yaw, pitch, up, vfov_deg)
        };
        // A view along `up` is allowed: `Camera::frame` picks another `right` axis for it.
        Ok(camera)
    }

    pub(super) fn path(&self, raw: &Spanned<RawPath>) -> Result<CameraPath, SceneError> {
        let r = raw.get_ref();
        let label = "path";
        let frames = match &r.frames {
            Some(f) if *f.get_ref() == 0 => {
                return Err(self.invalid(f.span(), "path: frames must be at least 1, got 0".into()));
            }
            Some(f) => *f.get_ref(),
            None => DEFAULT_FRAMES,
        };
        let duration_s = match &r.duration_s {
            Some(d) => Some(self.positive_seconds(label, "duration_s", d)?),
            None => None,
        };
        let mut keys = present_keys!(r, center, radius, height, keys);
        if let Some(l) = &r.looped {
            keys.push(("loop", l.span()));
        }
        let motion = match r.kind.get_ref().as_str() {
            "sweep" => {
                self.only_keys(label, "a sweep path", &keys, &[])?;
                PathMotion::Sweep
            }
            "orbit" => {
                self.only_keys(
                    label,
                    "an orbit path",
                    &keys,
                    &["center", "radius", "height"],
                )?;
                let center = self.vec3(
                    label,
                    "center",
                    self.required(label, "center", &r.center, raw)?,
                )?;
                let radius = self.positive(
                    label,
                    "radius",
                    self.required(label, "radius", &r.radius, raw)?,
                )?;
                let height = match &r.height {
                    Some(h) => self.number(label, "height", h)?,
                    None => 0.0,
                };
                PathMotion::Orbit {
                    center,
                    radius,
                    height,
                }
            }
            "pans" => {
                self.only_keys(label, "a pans path", &keys, &[])?;
                PathMotion::Pans
            }
            "keys" => {
                self.only_keys(label, "a keys path", &keys, &["keys", "loop"])?;
                let path = self.keyed_path(raw, frames, duration_s)?;
                PathMotion::Keys(path)
            }
            other => {
                return Err(self.invalid(
                    r.kind.span(),
                    format!(
                        "path: unknown path type {other:?} (expected \"sweep\", \"orbit\", \"pans\" or \"keys\")"
                    ),
                ));
            }
        };
        Ok(CameraPath {
            motion,
            frames,
            duration_s,
        })
    }

    /// The keys of a `type = "keys"` path: at least two, from t = 0, strictly increasing, all
    /// looking the same way; looped, all before the path's end.
    pub(super) fn keyed_path(
        &self,
        raw: &Spanned<RawPath>,
        frames: u32,
        duration_s: Option<f64>,
    ) -> Result<KeyedPath, SceneError> {
        let r = raw.get_ref();
        let raw_keys = self.required("path", "keys", &r.keys, raw)?;
        if raw_keys.get_ref().len() < 2 {
            return Err(self.invalid(
                raw_keys.span(),
                format!(
                    "path: a keys path needs at least two keys, got {}",
                    raw_keys.get_ref().len()
                ),
            ));
        }
        let mut keys: Vec<CameraKey> = Vec::with_capacity(raw_keys.get_ref().len());
        for (i, k) in raw_keys.get_ref().iter().enumerate() {
            let label = &format!("path: key {}", i + 1);
            let kr = k.get_ref();
            let t = self.seconds(label, "t", &kr.t)?;
            match keys.last() {
                None if t != 0.0 => {
                    return Err(self.invalid(
                        kr.t.span(),
                        format!("{label}: the first key must be at t = 0, got {t}"),
                    ));
                }
                Some(prev) if t <= prev.t => {
                    return Err(self.invalid(
                        kr.t.span(),
                        format!(
                            "{label}: key times must increase, but t = {t} is not after key \
                             {}'s t = {}",
                            i, prev.t
                        ),
                    ));
                }
                _ => {}
            }
            let eye = self.vec3(label, "eye", &kr.eye)?;
            if kr.pitch_deg.is_some() && kr.yaw_deg.is_none() {
                let span = kr.pitch_deg.as_ref().map_or(k.span(), |p| p.span());
                return Err(self.invalid(span, format!("{label}: pitch_deg needs yaw_deg")));
            }
            let look = match (&kr.target, &kr.yaw_deg) {
                (Some(t), None) => {
                    let target = self.vec3(label, "target", t)?;
                    if target == eye {
                        return Err(
                            self.invalid(t.span(), format!("{label}: target must differ from eye"))
                        );
                    }
                    KeyLook::Target(target)
                }
                (None, Some(y)) => KeyLook::YawPitch {
                    yaw_deg: self.number(label, "yaw_deg", y)?,
                    pitch_deg: match &kr.pitch_deg {
                        Some(p) => self.number(label, "pitch_deg", p)?,
                        None => 0.0,
                    },
                },
                (Some(_), Some(y)) => {
                    return Err(self.invalid(
                        y.span(),
                        format!("{label}: give `target` or `yaw_deg`, not both"),
                    ));
                }
                (None, None) => {
                    return Err(self.invalid(
                        k.span(),
                        format!("{label}: give `target` or `yaw_deg` (and `pitch_deg`)"),
                    ));
                }
            };
            if let Some(first) = keys.first()
                && matches!(first.look, KeyLook::Target(_)) != matches!(look, KeyLook::Target(_))
            {
                return Err(self.invalid(
                    k.span(),
                    format!(
                        "{label}: every key must look the same way, all with `target` or all \
                         with `yaw_deg`/`pitch_deg`, but key 1 uses {}",
                        if matches!(first.look, KeyLook::Target(_)) {
                            "`target`"
                        } else {
                            "`yaw_deg`"
                        }
                    ),
                ));
            }
            let vfov_deg = match &kr.vfov_deg {
                Some(v) => Some(self.field_of_view(label, v)?),
                None => None,
            };
            keys.push(CameraKey {
                t,
                eye,
                look,
                vfov_deg,
            });
        }
        let looped = r.looped.as_ref().is_some_and(|l| *l.get_ref());
        let duration = duration_s.unwrap_or(frames as f64 / 60.0);
        let last = keys[keys.len() - 1].t;
        if looped && last >= duration {
            return Err(self.invalid(
                raw_keys.span(),
                format!(
                    "path: a looped keys path runs from its last key back to its first by the \
                     path's end, so its last key (t = {last}) must come before duration_s \
                     ({duration} s{})",
                    if duration_s.is_none() {
                        ", from frames / 60"
                    } else {
                        ""
                    }
                ),
            ));
        }
        Ok(KeyedPath { keys, looped })
    }
}
