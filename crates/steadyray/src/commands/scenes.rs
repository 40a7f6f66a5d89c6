//! `steadyray scenes`: the built-in scenes.

/// Prints each built-in scene's name and description.
pub fn run() {
    for name in steadyray_scene::builtin_names() {
        let about = steadyray_scene::builtin_description(name).unwrap_or_default();
        let default = if *name == steadyray_scene::DEFAULT_SCENE {
            " (default)"
        } else {
            ""
        };
        println!("{name:<10} {about}{default}");
    }
}
