//! Which samples a plain frame draws, so that a reference shares none with the frames it
//! judges.

use crate::SettingsError;
use crate::temporal::{jitter, sample_base};

/// The frame slot whose samples references draw ([`SampleStream::Reference`]): the last of
/// the 2^20 slots that [`sample_base`] cycles through, which a temporal run reaches only
/// after 2^20 − 1 frames (almost five hours at 60 frames a second).
pub const REFERENCE_SLOT: u32 = 0xf_ffff;

/// Which samples a plain (not temporal) frame draws: where they lie in each pixel and the
/// random numbers that choose their dielectric branches.
///
/// Every frame draws the same ones: sample i of a pixel at its unjittered position with the
/// random numbers of index i (the samples of temporal frame slot 0). A reference drawn
/// alike contains a plain frame's samples (all S of them for an even S, the same positions
/// and the same branches), so the frame scores closer to it for sharing its noise, while a
/// temporal history, whose samples move every frame, does not: at 320x180 a plain S = 6
/// frame scored FLIP 0.0075 against such an S = 16 reference and 0.0093 against one of
/// S = 256, a history of 30 frames at S = 6 0.0087 and 0.0072 (`docs/quality.md`). A
/// reference therefore draws the samples of [`REFERENCE_SLOT`], which no frame draws.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SampleStream {
    /// Every frame's samples.
    #[default]
    Frames,
    /// The samples reserved for references: the jitter of [`REFERENCE_SLOT`] (its pairs of
    /// samples moved by ±J, so an image of S ≥ 2 keeps its centroid at the pixel centre; the
    /// one sample of S = 1 sits J off it) and random numbers from its sample base.
    Reference,
}

/// The fewest eye rays per pixel a reference may take: with one sample a pixel, its sample
/// sits the reserved jitter J off the pixel centre, and the whole image with it.
pub const MIN_REFERENCE_SPP: f32 = 2.0;

/// Checks that a reference of `spp` eye rays per pixel keeps its centroid at every pixel
/// centre (at least [`MIN_REFERENCE_SPP`]).
pub fn check_reference_spp(spp: f32) -> Result<(), SettingsError> {
    if spp >= MIN_REFERENCE_SPP {
        Ok(())
    } else {
        Err(SettingsError::BadReferenceSpp(spp))
    }
}

impl SampleStream {
    /// The stream's jitter (as [`crate::temporal::jittered_sample`] takes it) and its first
    /// sample index (the random numbers' index of sample 0).
    pub fn pattern(self) -> ([f32; 2], u32) {
        let slot = match self {
            Self::Frames => 0,
            Self::Reference => REFERENCE_SLOT,
        };
        (jitter(slot), sample_base(slot))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::MAX_SPP;

    #[test]
    fn a_reference_takes_two_samples_or_more() {
        assert!(check_reference_spp(2.0).is_ok() && check_reference_spp(256.0).is_ok());
        for bad in [1.0, 1.5, 0.0, f32::NAN] {
            let err = check_reference_spp(bad).unwrap_err().to_string();
            assert!(err.contains("S >= 2"), "{err}");
        }
    }

    #[test]
    fn frames_draw_the_unjittered_samples_and_references_others() {
        assert_eq!(SampleStream::Frames.pattern(), ([0.0; 2], 0));
        let (j, base) = SampleStream::Reference.pattern();
        assert!(j.iter().all(|&v| v > 0.1 && v < 0.9), "{j:?}");
        // A reference of the most samples a frame may take still fits in u32.
        assert!(u64::from(base) + MAX_SPP as u64 - 1 <= u64::from(u32::MAX));
        assert!(base >= sample_base(REFERENCE_SLOT - 1) + MAX_SPP as u32);
    }
}
