//! Value checks shared by every part of the file: known keys, required values, numbers,
//! times, vectors and colours.

use super::*;

impl Cx<'_> {
    /// Rejects keys of `keys` that are not in `allowed` for a table of this kind.
    pub(super) fn only_keys(
        &self,
        label: &str,
        kind: &str,
        keys: &[(&'static str, Range<usize>)],
        allowed: &[&str],
    ) -> Result<(), SceneError> {
        match keys.iter().find(|(k, _)| !allowed.contains(k)) {
            Some((key, span)) => Err(self.invalid(
                span.clone(),
                format!(
                    "{label}: key `{key}` does not apply to {kind} (it takes {})",
                    if allowed.is_empty() {
                        "only `frames` and `duration_s`".to_owned()
                    } else {
                        allowed
                            .iter()
                            .map(|k| format!("`{k}`"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    }
                ),
            )),
            None => Ok(()),
        }
    }

    pub(super) fn required<'v, T, U>(
        &self,
        label: &str,
        key: &str,
        value: &'v Option<Spanned<T>>,
        table: &Spanned<U>,
    ) -> Result<&'v Spanned<T>, SceneError> {
        value
            .as_ref()
            .ok_or_else(|| self.invalid(table.span(), format!("{label}: missing `{key}`")))
    }

    pub(super) fn number(
        &self,
        label: &str,
        key: &str,
        v: &Spanned<f32>,
    ) -> Result<f32, SceneError> {
        let x = *v.get_ref();
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.invalid(
                v.span(),
                format!("{label}: {key} must be a finite number, got {x}"),
            ))
        }
    }

    pub(super) fn field_of_view(&self, label: &str, v: &Spanned<f32>) -> Result<f32, SceneError> {
        let f = self.number(label, "vfov_deg", v)?;
        if f > 0.0 && f < 180.0 {
            Ok(f)
        } else {
            Err(self.invalid(
                v.span(),
                format!("{label}: vfov_deg must be in (0, 180) degrees, got {f}"),
            ))
        }
    }

    /// A time in seconds: any finite number.
    pub(super) fn seconds(
        &self,
        label: &str,
        key: &str,
        v: &Spanned<f64>,
    ) -> Result<f64, SceneError> {
        let x = *v.get_ref();
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.invalid(
                v.span(),
                format!("{label}: {key} must be a finite number of seconds, got {x}"),
            ))
        }
    }

    pub(super) fn positive_seconds(
        &self,
        label: &str,
        key: &str,
        v: &Spanned<f64>,
    ) -> Result<f64, SceneError> {
        let x = self.seconds(label, key, v)?;
        if x > 0.0 {
            Ok(x)
        } else {
            Err(self.invalid(
                v.span(),
                format!("{label}: {key} must be positive, got {x}"),
            ))
        }
    }

    pub(super) fn positive(
        &self,
        label: &str,
        key: &str,
        v: &Spanned<f32>,
    ) -> Result<f32, SceneError> {
        let x = self.number(label, key, v)?;
        if x > 0.0 {
            Ok(x)
        } else {
            Err(self.invalid(
                v.span(),
                format!("{label}: {key} must be positive, got {x}"),
            ))
        }
    }

    pub(super) fn non_negative(
        &self,
        label: &str,
        key: &str,
        v: &Spanned<f32>,
    ) -> Result<f32, SceneError> {
        let x = self.number(label, key, v)?;
        if x >= 0.0 {
            Ok(x)
        } else {
            Err(self.invalid(
                v.span(),
                format!("{label}: {key} must not be negative, got {x}"),
            ))
        }
    }

    pub(super) fn vec3(&self, label: &str, key: &str, v: &Spanned<V3>) -> Result<Vec3, SceneError> {
        let p = Vec3::from(*v.get_ref());
        if p.is_finite() {
            Ok(p)
        } else {
            Err(self.invalid(v.span(), format!("{label}: {key} must be finite, got {p}")))
        }
    }

    pub(super) fn nonzero(
        &self,
        label: &str,
        key: &str,
        v: &Spanned<V3>,
    ) -> Result<Vec3, SceneError> {
        let p = self.vec3(label, key, v)?;
        if p != Vec3::ZERO {
            Ok(p)
        } else {
            Err(self.invalid(v.span(), format!("{label}: {key} must not be zero-length")))
        }
    }

    /// A colour (or intensity): finite and not negative.
    pub(super) fn colour(
        &self,
        label: &str,
        key: &str,
        v: &Spanned<Triple>,
    ) -> Result<Vec3, SceneError> {
        let c = Vec3::from(v.get_ref().0);
        if !c.is_finite() {
            return Err(self.invalid(v.span(), format!("{label}: {key} must be finite, got {c}")));
        }
        if c.min_element() < 0.0 {
            return Err(self.invalid(
                v.span(),
                format!("{label}: {key} must not be negative, got {c}"),
            ));
        }
        Ok(c)
    }
}
