//! Draws a [`NoiseProfile`]'s factors, seeded and deterministic.

use super::profile::NoiseProfile;
use crate::simulate::Pcg32;

/// The noise of one run: each call of [`NoiseProcess::factor`] gives the next frame's time
/// factor. It draws the same random numbers every frame whatever happens, so two runs with
/// one seed meet the same jitter, spikes and spell shocks, only the spells' decay following
/// the time that passed between frames.
#[derive(Clone, Debug)]
pub struct NoiseProcess {
    profile: NoiseProfile,
    rng: Pcg32,
    /// ln(machine speed factor) now.
    spell: f64,
}

impl NoiseProcess {
    /// A process for `profile` (assumed valid, see [`NoiseProfile::validate`]) from `seed`;
    /// the spell starts at a draw from its stationary spread.
    pub fn new(profile: NoiseProfile, seed: u64) -> Self {
        let mut rng = Pcg32::new(seed);
        let spell = profile.spell_sigma * rng.normal();
        Self {
            profile,
            rng,
            spell,
        }
    }

    /// The profile it replays.
    pub fn profile(&self) -> &NoiseProfile {
        &self.profile
    }

    /// The time factor of the next frame, `elapsed_ms` after the previous one started (the
    /// spell decays over that time).
    pub fn factor(&mut self, elapsed_ms: f64) -> f64 {
        let p = &self.profile;
        let keep = (-elapsed_ms.max(0.0) / p.spell_ms).exp();
        let shock = self.rng.normal();
        let jitter = self.rng.normal();
        let spike_draw = self.rng.unit();
        let spike_size = self.rng.normal();
        self.spell = keep * self.spell + (1.0 - keep * keep).sqrt() * p.spell_sigma * shock;
        let spike = if spike_draw < p.spike_prob {
            (p.spike_log_mean + p.spike_log_sd * spike_size).max(0.0)
        } else {
            0.0
        };
        (self.spell + p.jitter_sigma * jitter + spike).exp()
    }
}
