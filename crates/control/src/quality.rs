//! What a controller chooses: the quality of the next frame, its bounds and the knobs' order.

use crate::error::ConfigError;
use serde::{Deserialize, Serialize};
use std::cmp::Ordering;
use std::fmt;
use std::str::FromStr;

/// The quality of one frame: the three knobs a controller turns.
///
/// - `spp` (S): eye rays per pixel. Fractional values are allowed: the renderer gives each
///   pixel floor(S) or floor(S) + 1 samples by a fixed dither, so the mean is S.
/// - `depth` (R): the largest number of reflection/refraction events on a path (0: local
///   shading only).
/// - `scale`: the resolution scale in (0, 1]; the frame has about scale² of the full pixels.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Quality {
    /// Eye rays per pixel (S); may be fractional.
    pub spp: f32,
    /// Reflection depth (R): the most reflection/refraction events on a path (0: local shading).
    pub depth: u32,
    /// Resolution scale in (0, 1].
    pub scale: f32,
}

impl Quality {
    /// A quality from its three knobs (not checked: see [`Bounds::contains`]).
    pub const fn new(spp: f32, depth: u32, scale: f32) -> Self {
        Self { spp, depth, scale }
    }

    /// A scalar "level" for reports and plots: the nominal rays per full-resolution pixel,
    /// scale² · S · (R + 1), i.e. the work this quality asks for if every ray bounced R times.
    pub fn level(&self) -> f64 {
        let scale = f64::from(self.scale);
        scale * scale * f64::from(self.spp) * f64::from(self.depth + 1)
    }

    /// A total order over qualities: by [`Quality::level`], ties broken by depth, then S, then
    /// scale. Metrics use it to give every quality change a direction (up or down).
    pub fn cmp_level(&self, other: &Quality) -> Ordering {
        self.level()
            .total_cmp(&other.level())
            .then(self.depth.cmp(&other.depth))
            .then(self.spp.total_cmp(&other.spp))
            .then(self.scale.total_cmp(&other.scale))
    }

    /// Whether every knob is at least `other`'s (e.g. "at the highest quality").
    pub fn at_least(&self, other: &Quality) -> bool {
        self.spp >= other.spp && self.depth >= other.depth && self.scale >= other.scale
    }

    /// The value of one knob, as a number.
    pub fn get(&self, knob: Knob) -> f64 {
        match knob {
            Knob::Spp => f64::from(self.spp),
            Knob::Depth => f64::from(self.depth),
            Knob::Scale => f64::from(self.scale),
        }
    }

    /// This quality with one knob set (depth is rounded to the nearest whole number).
    pub fn with(mut self, knob: Knob, value: f64) -> Self {
        match knob {
            Knob::Spp => self.spp = value as f32,
            Knob::Depth => self.depth = value.round().max(0.0) as u32,
            Knob::Scale => self.scale = value as f32,
        }
        self
    }
}

impl fmt::Display for Quality {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "S={} R={} scale={}", self.spp, self.depth, self.scale)
    }
}

/// One quality knob.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Knob {
    /// Eye rays per pixel S (continuous for hysteresis and predictive, whole for step).
    Spp,
    /// Reflection/refraction depth R (always whole).
    Depth,
    /// Resolution scale (continuous).
    Scale,
}

impl Knob {
    /// The knob's name as written in options: `spp`, `depth`, `scale`.
    pub fn name(self) -> &'static str {
        match self {
            Knob::Spp => "spp",
            Knob::Depth => "depth",
            Knob::Scale => "scale",
        }
    }
}

impl FromStr for Knob {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.trim() {
            "spp" | "s" | "S" => Ok(Knob::Spp),
            "depth" | "r" | "R" => Ok(Knob::Depth),
            "scale" => Ok(Knob::Scale),
            other => Err(format!(
                "unknown knob `{other}`: expected spp, depth or scale"
            )),
        }
    }
}

/// The order in which a controller raises knobs (it cuts in the reverse order). Knobs left
/// out are not controlled: they keep the starting quality's value.
///
/// Written `depth,scale,spp` in options (the default: reflections first, then resolution,
/// then samples; so an overloaded frame loses samples first, then resolution, then depth).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct KnobOrder(Vec<Knob>);

impl KnobOrder {
    /// An order from a non-empty list of distinct knobs.
    pub fn new(knobs: Vec<Knob>) -> Result<Self, String> {
        if knobs.is_empty() {
            return Err("the knob order is empty: name at least one of depth, spp, scale".into());
        }
        for (i, k) in knobs.iter().enumerate() {
            if knobs[..i].contains(k) {
                return Err(format!("knob `{}` appears twice in the order", k.name()));
            }
        }
        Ok(Self(knobs))
    }

    /// The knobs in raising order.
    pub fn knobs(&self) -> &[Knob] {
        &self.0
    }

    /// Whether the order controls `knob`.
    pub fn contains(&self, knob: Knob) -> bool {
        self.0.contains(&knob)
    }
}

/// The default order: R, then resolution, then S. Raising the scale before S means that
/// under load S is cut first, then resolution: raising S first lets a controller ratchet
/// into many samples per pixel at a fraction of the resolution (seen on the real corridor:
/// S = 12 at scale 0.35), which looks worse than S = 1 at full resolution.
impl Default for KnobOrder {
    fn default() -> Self {
        Self(vec![Knob::Depth, Knob::Scale, Knob::Spp])
    }
}

impl FromStr for KnobOrder {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let knobs = s
            .split([',', '>', '+'])
            .filter(|p| !p.trim().is_empty())
            .map(str::parse)
            .collect::<Result<Vec<Knob>, String>>()?;
        Self::new(knobs)
    }
}

impl fmt::Display for KnobOrder {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<&str> = self.0.iter().map(|k| k.name()).collect();
        f.write_str(&names.join(","))
    }
}

/// The range each knob may take. Default: S in [1, 256], R in [0, 16], scale in [0.25, 1].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Bounds {
    /// Fewest eye rays per pixel, at least 1.
    pub spp_min: f32,
    /// Most eye rays per pixel.
    pub spp_max: f32,
    /// Smallest reflection depth.
    pub depth_min: u32,
    /// Largest reflection depth.
    pub depth_max: u32,
    /// Smallest resolution scale, > 0.
    pub scale_min: f32,
    /// Largest resolution scale, at most 1.
    pub scale_max: f32,
}

impl Default for Bounds {
    fn default() -> Self {
        Self {
            spp_min: 1.0,
            spp_max: 256.0,
            depth_min: 0,
            depth_max: 16,
            scale_min: 0.25,
            scale_max: 1.0,
        }
    }
}

impl fmt::Display for Bounds {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "S in [{}, {}], R in [{}, {}], scale in [{}, {}]",
            self.spp_min,
            self.spp_max,
            self.depth_min,
            self.depth_max,
            self.scale_min,
            self.scale_max
        )
    }
}

impl Bounds {
    /// Checked bounds: S >= 1, min <= max for every knob, 0 < scale <= 1, all finite.
    pub fn new(spp: (f32, f32), depth: (u32, u32), scale: (f32, f32)) -> Result<Self, ConfigError> {
        let b = Self {
            spp_min: spp.0,
            spp_max: spp.1,
            depth_min: depth.0,
            depth_max: depth.1,
            scale_min: scale.0,
            scale_max: scale.1,
        };
        b.validate()?;
        Ok(b)
    }

    /// The bounds of an engine whose one knob is the render scale, from `min_scale` to
    /// `max_scale`: one sample per pixel, no bounces (a raster engine's dynamic resolution).
    pub fn scale_only(min_scale: f32, max_scale: f32) -> Result<Self, ConfigError> {
        Self::new((1.0, 1.0), (0, 0), (min_scale, max_scale))
    }

    /// Checks the bounds (the fields are public, so controllers check again when built).
    pub fn validate(&self) -> Result<(), ConfigError> {
        let bad = |knob, min: f64, max: f64, why| {
            Err(ConfigError::BadBounds {
                knob,
                min,
                max,
                why,
            })
        };
        let (smin, smax) = (f64::from(self.spp_min), f64::from(self.spp_max));
        if !(smin.is_finite() && smax.is_finite()) {
            return bad("spp", smin, smax, "must be finite numbers");
        }
        if smin < 1.0 {
            return bad("spp", smin, smax, "S is at least 1 eye ray per pixel");
        }
        if smin > smax {
            return bad("spp", smin, smax, "min > max");
        }
        if self.depth_min > self.depth_max {
            let (dmin, dmax) = (f64::from(self.depth_min), f64::from(self.depth_max));
            return bad("depth", dmin, dmax, "min > max");
        }
        let (cmin, cmax) = (f64::from(self.scale_min), f64::from(self.scale_max));
        if !(cmin > 0.0 && cmax <= 1.0) {
            return bad("scale", cmin, cmax, "the scale must lie in (0, 1]");
        }
        if cmin > cmax {
            return bad("scale", cmin, cmax, "min > max");
        }
        Ok(())
    }

    /// The lowest quality: every knob at its minimum.
    pub fn min_quality(&self) -> Quality {
        Quality::new(self.spp_min, self.depth_min, self.scale_min)
    }

    /// The highest quality: every knob at its maximum.
    pub fn max_quality(&self) -> Quality {
        Quality::new(self.spp_max, self.depth_max, self.scale_max)
    }

    /// The range of one knob, as numbers.
    pub fn range(&self, knob: Knob) -> (f64, f64) {
        match knob {
            Knob::Spp => (f64::from(self.spp_min), f64::from(self.spp_max)),
            Knob::Depth => (f64::from(self.depth_min), f64::from(self.depth_max)),
            Knob::Scale => (f64::from(self.scale_min), f64::from(self.scale_max)),
        }
    }

    /// Whether `q` lies inside the bounds (NaN knobs do not).
    pub fn contains(&self, q: &Quality) -> bool {
        q.spp >= self.spp_min
            && q.spp <= self.spp_max
            && q.depth >= self.depth_min
            && q.depth <= self.depth_max
            && q.scale >= self.scale_min
            && q.scale <= self.scale_max
    }

    /// `q` moved inside the bounds (a NaN knob becomes the knob's minimum).
    pub fn clamp(&self, q: Quality) -> Quality {
        let clamp = |v: f32, lo: f32, hi: f32| if v.is_nan() { lo } else { v.clamp(lo, hi) };
        Quality {
            spp: clamp(q.spp, self.spp_min, self.spp_max),
            depth: q.depth.clamp(self.depth_min, self.depth_max),
            scale: clamp(q.scale, self.scale_min, self.scale_max),
        }
    }

    /// The fixed qualities along one knob, lowest first, the other knobs as in `base`:
    /// every whole R, every whole S, or scales from the maximum down in steps of 0.05. The
    /// candidates for the "most-in-band fixed quality" baseline (see
    /// [`crate::metrics::most_in_band_fixed`]).
    pub fn ladder(&self, knob: Knob, base: Quality) -> Result<Vec<Quality>, ConfigError> {
        self.validate()?;
        let base = self.clamp(base);
        let (lo, hi) = self.range(knob);
        let values: Vec<f64> = match knob {
            Knob::Depth => (self.depth_min..=self.depth_max).map(f64::from).collect(),
            Knob::Spp => {
                let (first, last) = (lo.ceil() as u64, hi.floor() as u64);
                (first..=last).map(|s| s as f64).collect()
            }
            Knob::Scale => {
                let mut v: Vec<f64> = (0..)
                    .map(|i| hi - 0.05 * f64::from(i))
                    .take_while(|s| *s >= lo - 1e-9)
                    .map(|s| s.max(lo))
                    .collect();
                v.reverse();
                v
            }
        };
        if values.is_empty() {
            return Err(ConfigError::EmptyLadder {
                knob: knob.name(),
                min: lo,
                max: hi,
            });
        }
        Ok(values.into_iter().map(|v| base.with(knob, v)).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn level_orders_work() {
        let lo = Quality::new(1.0, 0, 1.0);
        let hi = Quality::new(1.0, 1, 1.0);
        assert_eq!(lo.cmp_level(&hi), Ordering::Less);
        assert_eq!(hi.cmp_level(&hi), Ordering::Equal);
        // Same level (1 ray per full pixel): the tie goes to the larger S.
        assert_eq!(Quality::new(4.0, 0, 0.5).cmp_level(&lo), Ordering::Greater);
    }

    #[test]
    fn bounds_reject_inverted_ranges() {
        assert!(matches!(
            Bounds::new((4.0, 2.0), (0, 16), (0.25, 1.0)),
            Err(ConfigError::BadBounds { knob: "spp", .. })
        ));
        assert!(Bounds::new((1.0, 2.0), (3, 2), (0.25, 1.0)).is_err());
        assert!(Bounds::new((1.0, 2.0), (0, 2), (0.0, 1.0)).is_err());
        assert!(Bounds::new((1.0, f32::NAN), (0, 2), (0.5, 1.0)).is_err());
        assert!(Bounds::new((0.5, 2.0), (0, 2), (0.5, 1.0)).is_err());
    }

    #[test]
    fn ladders() {
        let b = Bounds::default();
        let base = b.max_quality();
        assert_eq!(b.ladder(Knob::Depth, base).unwrap().len(), 17);
        assert_eq!(b.ladder(Knob::Spp, base).unwrap().len(), 256);
        let scales = b.ladder(Knob::Scale, base).unwrap();
        assert_eq!(scales.len(), 16);
        assert_eq!(scales[0].scale, 0.25);
        assert_eq!(scales[15].scale, 1.0);
        let narrow = Bounds::new((1.2, 1.8), (0, 2), (0.5, 1.0)).unwrap();
        assert!(matches!(
            narrow.ladder(Knob::Spp, base),
            Err(ConfigError::EmptyLadder { .. })
        ));
    }

    #[test]
    fn knob_order_parses() {
        let o: KnobOrder = "depth,spp,scale".parse().unwrap();
        assert_ne!(o, KnobOrder::default());
        assert_eq!(KnobOrder::default().to_string(), "depth,scale,spp");
        assert!("depth,depth".parse::<KnobOrder>().is_err());
        assert!("".parse::<KnobOrder>().is_err());
        assert!("depth,colour".parse::<KnobOrder>().is_err());
        assert_eq!(o.to_string(), "depth,spp,scale");
    }
}
