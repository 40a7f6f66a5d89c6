//! Motion on screen: how fast what a frame shows moves, as the viewer sees it.
//!
//! Per frame, a grid of 32 columns of eye rays (0.25 % of a 640x360 frame's) is cast into
//! the scene on the CPU; each primary hit (or, for a ray that leaves the scene, its
//! direction) is projected into the previous frame's camera, both positions are placed on
//! the display of the viewing set-up every metric uses (`ViewingSetup::standard_fhd`: a
//! 24-inch 1920x1080 display at 0.6 m, the picture shown full screen), and the visual angle
//! between the eye's directions to them over the time between the frames is the sample's
//! speed. A frame reports the mean and the 95th percentile over the grid, in degrees of visual
//! angle per second ([`ScreenSpeed`]). The controllers see the mean
//! (`FrameReport::speed_deg_s`): the speed of what most of the picture shows, which is what
//! the stimuli of `calibrate --motion` are measured by as well.
//!
//! [`MotionTracker`] follows a run: a frame that shows the same world time as the one before
//! it (the real clock renders two frames at one time when the first is shown a refresh early)
//! reports that frame's motion rather than none.
//!
//! Objects are still in today's scenes: the camera's change is the only motion. The probe
//! runs outside the render's timing (it is not part of Tp); on the corridor it traces 576 rays
//! per frame.

pub mod probe;
pub mod speed;

pub use probe::{GRID_COLUMNS, MotionProbe, MotionTracker, Shot};
pub use speed::{ScreenSpeed, Seen, sample_speeds};
