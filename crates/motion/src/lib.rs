//! Motion on screen: how fast what a frame shows moves, as the viewer sees it.
//!
//! Per frame, a grid of 32 columns of eye rays (0.25 % of a 640x360 frame's) is cast into
//! the world at the frame's scene time on the CPU; each primary hit is carried back by its
//! object's motion (`[shapes.motion]`; still objects stay put) to where it was at the previous
//! frame's time, and projected into the previous frame's camera (a ray that leaves the scene
//! counts as a direction: the background turns with the camera but does not move with it).
//! Both positions are placed on the display of the viewing set-up every metric uses
//! (`ViewingSetup::standard_fhd`: a 24-inch 1920x1080 display at 0.6 m, the picture shown full
//! screen), and the visual angle between the eye's directions to them over the time between
//! the frames is the sample's speed. A frame reports the mean and the 95th percentile over
//! the grid, in degrees of visual angle per second ([`ScreenSpeed`]). The controllers see the
//! mean (`FrameReport::speed_deg_s`): the speed of what most of the picture shows, which is
//! what the stimuli of `calibrate --motion` are measured by as well.
//!
//! [`MotionTracker`] follows a run: a frame that shows the same time as the one before it
//! (the real clock renders two frames at one time when the first is shown a refresh early)
//! reports that frame's motion rather than none.
//!
//! The probe runs outside the render's timing (it is not part of Tp): 576 rays per frame on
//! one thread, about 0.25 ms on the corridor.

pub mod probe;
pub mod speed;

pub use probe::{GRID_COLUMNS, MotionProbe, MotionTracker, Shot};
pub use speed::{ScreenSpeed, Seen, sample_speeds};
