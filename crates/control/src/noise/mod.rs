//! Machine timing noise you can replay: a model of how a real machine's frame times wander
//! at a fixed quality, fitted from recorded runs and replayed, seeded, by the simulated
//! renderer ([`crate::simulate`]), so controllers are tested and tuned on the noise that
//! real machines make rather than on ideal Gaussian noise.
//!
//! A frame's time is its noise-free time times a factor with three parts
//! ([`NoiseProfile`]):
//! - **jitter**: frame-to-frame log-normal noise, independent from frame to frame;
//! - **spikes**: single frames slowed by a log-normal factor, at random;
//! - **spells**: the machine's speed drifting slower and faster for seconds (another process
//!   on the machine, clocks, caches): a log-normal AR(1) process in time, with a stationary
//!   spread and a correlation time.
//!
//! [`fit_profile`] estimates the parameters from the frame times of fixed-quality runs:
//! jitter and spikes from each frame against its neighbours, spells from the slow ratio of
//! two runs of the same frames. [`NoiseProcess`] draws the factors. Everything here is a pure
//! function of slices and seeds: reading and writing files is left to the caller.

mod fit;
mod process;
mod profile;

pub use fit::{NoiseFit, SpikeFit, fit_profile};
pub use process::NoiseProcess;
pub use profile::{NoiseError, NoiseProfile};
