//! The table of every controller's options: name, key, default and meaning. The parsers'
//! "it takes ..." messages and `steadyray controllers` are both made from it, so what the
//! help lists and what the parser accepts cannot drift (a test checks that each key listed
//! is accepted and each accepted key is listed).

/// One option of one controller, as written in `name:key=value`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OptionInfo {
    /// The controller that takes it (`fixed`, `step`, ...).
    pub controller: &'static str,
    /// The key.
    pub key: &'static str,
    /// Its default, as written on the command line.
    pub default: &'static str,
    /// What it does, in one line.
    pub meaning: &'static str,
}

/// One line describing each controller, in the order they are listed.
pub const CONTROLLERS: &[(&str, &str)] = &[
    (
        "fixed",
        "holds one quality whatever the frame time (the paper's baseline)",
    ),
    (
        "step",
        "one step of a knob per frame out of the band (the paper's controller)",
    ),
    (
        "hysteresis",
        "soft limits inside the band, cuts at once and raises after headroom",
    ),
    (
        "predictive",
        "a cost model of the frame picks the quality predicted to land in the band",
    ),
    (
        "perceptual",
        "predictive, with the frame time that looks best at the measured speed (by a \
         shipped quality model unless given one)",
    ),
];

const fn opt(
    controller: &'static str,
    key: &'static str,
    default: &'static str,
    meaning: &'static str,
) -> OptionInfo {
    OptionInfo {
        controller,
        key,
        default,
        meaning,
    }
}

/// The options of `predictive` that `perceptual` takes too (all but `ladder`): key,
/// default, meaning.
pub const PREDICTIVE_SHARED: &[(&str, &str, &str)] = &[
    (
        "order",
        "depth,scale,spp",
        "knobs in raising order; cut in reverse",
    ),
    (
        "target",
        "0.5",
        "the time a change aims for, as a fraction of the band",
    ),
    (
        "deadband",
        "0.2",
        "the inner band's margin, as a fraction of the band",
    ),
    (
        "min_reach",
        "0.02",
        "R is raised first only while this fraction of eye rays reaches deeper",
    ),
    (
        "max_raise",
        "2",
        "the largest factor on predicted rays per raise",
    ),
    (
        "trend",
        "0.5",
        "weight of the newest growth in the load trend (0: none)",
    ),
    (
        "measured_cut",
        "true",
        "frames measured above the inner band cut even when the model says it fits",
    ),
    (
        "trades",
        "true",
        "inside the inner band, trade knobs to where the order settles for the view",
    ),
    (
        "budget",
        "false",
        "hand each frame a time budget a progressive renderer keeps it in the band by",
    ),
    (
        "forgetting",
        "0.95",
        "the cost model's weight decay per frame, in (0, 1]",
    ),
    (
        "outlier_k",
        "4",
        "the cost model's outlier threshold, in robust standard deviations",
    ),
    (
        "confirm",
        "2",
        "outliers in a row on one side that confirm a real change of cost",
    ),
];

/// Every controller's own options (`predictive` and `perceptual` also take
/// [`PREDICTIVE_SHARED`]'s; [`options_of`] gives a controller's whole list).
pub const OPTIONS: &[OptionInfo] = &[
    opt(
        "fixed",
        "spp",
        "the start's S",
        "the eye rays per pixel it holds",
    ),
    opt(
        "fixed",
        "depth",
        "the start's R",
        "the reflection depth it holds",
    ),
    opt(
        "fixed",
        "scale",
        "the start's scale",
        "the resolution scale it holds",
    ),
    opt(
        "step",
        "knob",
        "depth",
        "the knob it steps: depth, spp or both",
    ),
    opt(
        "hysteresis",
        "order",
        "depth,scale,spp",
        "knobs in raising order; cut in reverse",
    ),
    opt(
        "hysteresis",
        "target",
        "0.4",
        "where in the band a change aims, as a fraction",
    ),
    opt(
        "hysteresis",
        "cut_above",
        "0.8",
        "the soft upper limit, as a fraction of the band",
    ),
    opt(
        "hysteresis",
        "cut_after",
        "1",
        "frames in a row above the soft limit before a cut",
    ),
    opt(
        "hysteresis",
        "raise_below",
        "0.3",
        "the headroom limit, as a fraction of the band",
    ),
    opt(
        "hysteresis",
        "up_after",
        "3",
        "frames in a row with headroom before a raise",
    ),
    opt(
        "hysteresis",
        "max_up",
        "0.3",
        "the largest relative increase of work per raise",
    ),
    opt(
        "hysteresis",
        "min_interval",
        "3",
        "frames between changes (over Tmax cuts regardless)",
    ),
    opt(
        "hysteresis",
        "hitch_ratio",
        "3",
        "a frame over Tmax this many times slower is a possible hitch",
    ),
    opt(
        "predictive",
        "ladder",
        "none",
        "a calibrated ladder file (ladder.json) to move along instead of order",
    ),
    opt(
        "perceptual",
        "model",
        "the shipped one",
        "a quality model file (motion.json of calibrate --motion), e.g. the scene's own",
    ),
    opt(
        "perceptual",
        "hold_ms",
        "500",
        "display time, ms, between two changes of the target",
    ),
    opt(
        "perceptual",
        "margin",
        "0.02",
        "how much better another frame time must score to be taken",
    ),
    opt(
        "perceptual",
        "fall_ms",
        "300",
        "time constant, ms, of the speed falling toward a lower one",
    ),
    opt(
        "perceptual",
        "hand_over",
        "1",
        "ms from a frame's render end to the display",
    ),
    opt(
        "perceptual",
        "warp",
        "0",
        "the cost of a warped refresh, ms (0: no warps)",
    ),
    opt(
        "perceptual",
        "slack",
        "0.05",
        "fraction of the frame time kept free for timing noise",
    ),
    opt(
        "perceptual",
        "width",
        "0.2",
        "the band's width as a fraction of its frame time",
    ),
];

/// The options of `controller`: for `predictive` the shared ones and `ladder`, for
/// `perceptual` its own and the predictive ones it passes on; empty for an unknown name.
pub fn options_of(controller: &'static str) -> Vec<OptionInfo> {
    let shared = PREDICTIVE_SHARED
        .iter()
        .map(|&(key, default, meaning)| opt(controller, key, default, meaning));
    let own = OPTIONS
        .iter()
        .filter(|o| o.controller == controller)
        .copied();
    match controller {
        "predictive" => shared.chain(own).collect(),
        "perceptual" => own.chain(shared).collect(),
        _ => own.collect(),
    }
}

/// The keys `controller` takes, comma separated: the parsers' "it takes ..." message.
pub fn expected_keys(controller: &'static str) -> String {
    let keys: Vec<&str> = options_of(controller).iter().map(|o| o.key).collect();
    keys.join(", ")
}

/// Every controller, a line each, with its options, defaults and meanings: the text of
/// `steadyray controllers`. Options are written `name:key=value`.
pub fn describe_controllers() -> String {
    let mut text = String::new();
    for (name, line) in CONTROLLERS {
        text.push_str(&format!("{name}: {line}\n"));
        for o in options_of(name) {
            let default = format!("(default {})", o.default);
            text.push_str(&format!("    {:<13} {default:<27} {}\n", o.key, o.meaning));
        }
    }
    text
}
