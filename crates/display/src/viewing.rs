//! The viewing set-up every metric of what the viewer sees assumes: one display, its size,
//! resolution and distance, with every frame shown full screen (upscaled when rendered
//! smaller).

use crate::error::DisplayError;
use serde::{Deserialize, Serialize};

/// A display seen from a distance.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ViewingSetup {
    /// ColorVideoVDP's name of the display (its photometry: peak luminance, contrast,
    /// ambient light), so that the JOD tool and the Rust metrics see the same display.
    pub name: String,
    /// Diagonal, inches.
    pub diagonal_in: f64,
    /// The panel's pixels.
    pub resolution: [u32; 2],
    /// Eye to screen, m.
    pub distance_m: f64,
}

impl ViewingSetup {
    /// ColorVideoVDP's `standard_fhd`: a 24-inch 1920x1080 monitor of 200 cd/m² under office
    /// light (250 lux), seen from 0.6 m. The set-up `bench` states and every metric uses.
    pub fn standard_fhd() -> Self {
        Self {
            name: "standard_fhd".into(),
            diagonal_in: 24.0,
            resolution: [1920, 1080],
            distance_m: 0.6,
        }
    }

    /// Checks that size, distance and resolution are positive and finite.
    pub fn validate(&self) -> Result<(), DisplayError> {
        let [w, h] = self.resolution;
        let ok = self.diagonal_in.is_finite()
            && self.diagonal_in > 0.0
            && self.distance_m.is_finite()
            && self.distance_m > 0.0
            && w > 0
            && h > 0;
        if ok {
            Ok(())
        } else {
            Err(DisplayError::BadViewing(format!(
                "{}: {} inches, {w}x{h} pixels, {} m (all must be above 0)",
                self.name, self.diagonal_in, self.distance_m
            )))
        }
    }

    /// The screen's width, m.
    pub fn width_m(&self) -> f64 {
        let [w, h] = self.resolution.map(f64::from);
        self.diagonal_in * 0.0254 * w / w.hypot(h)
    }

    /// Pixels per degree of visual angle at the screen's centre for an image `image_width`
    /// pixels wide shown full screen: the same formula as ColorVideoVDP's display geometry
    /// (one pixel's angle, inverted), which FLIP takes as its viewing condition.
    pub fn pixels_per_degree(&self, image_width: u32) -> f64 {
        let pixel_m = self.width_m() / f64::from(image_width.max(1));
        let pixel_deg = 2.0 * (0.5 * pixel_m / self.distance_m).atan().to_degrees();
        1.0 / pixel_deg
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn standard_fhd_geometry() {
        let s = ViewingSetup::standard_fhd();
        s.validate().unwrap();
        // 24 inches at 16:9: 0.531 m wide.
        assert!((s.width_m() - 0.5313).abs() < 1e-3, "{}", s.width_m());
        // ColorVideoVDP 0.5.7's display geometry gives 37.8425 (and 12.6142 for 640 wide).
        let ppd = s.pixels_per_degree(1920);
        assert!((ppd - 37.8425).abs() < 1e-3, "{ppd}");
        // A 640-pixel frame shown full screen: three display pixels per image pixel.
        assert!((s.pixels_per_degree(640) - ppd / 3.0).abs() < 0.01);
        let bad = ViewingSetup {
            distance_m: 0.0,
            ..ViewingSetup::standard_fhd()
        };
        assert!(bad.validate().unwrap_err().to_string().contains("0 m"));
    }
}
