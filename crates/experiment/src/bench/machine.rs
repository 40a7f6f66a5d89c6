//! Describing the machine and the source revision in reports.

use serde::Serialize;
use std::path::Path;
use std::process::Command;

/// The machine a benchmark ran on.
#[derive(Clone, Debug, Serialize)]
pub struct Machine {
    /// The host name.
    pub hostname: String,
    /// The CPU's model name.
    pub cpu: String,
    /// Hardware threads available.
    pub threads: usize,
    /// Operating system and architecture.
    pub os: String,
}

impl Machine {
    /// Reads the machine's description; unknown parts say "unknown".
    pub fn detect() -> Self {
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|text| {
                text.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split_once(':'))
                    .map(|(_, v)| v.trim().to_string())
            })
            .unwrap_or_else(|| "unknown".into());
        let hostname = std::fs::read_to_string("/etc/hostname")
            .map(|s| s.trim().to_string())
            .unwrap_or_else(|_| "unknown".into());
        Self {
            hostname,
            cpu,
            threads: std::thread::available_parallelism().map_or(1, |n| n.get()),
            os: format!("{} {}", std::env::consts::OS, std::env::consts::ARCH),
        }
    }
}

/// The sources a reference picture depends on, relative to the repository's root: the
/// renderers and their acceleration structures, the scene format (worlds, motion, camera
/// paths), the bench's and `calibrate --motion`'s reference rendering, and the locked
/// dependencies. A commit that touches none of them (a controller, a report, the docs)
/// renders the same references, so [`reference_revision`] keys them by the last commit that
/// did.
pub const REFERENCE_SOURCES: [&str; 10] = [
    "crates/render",
    "crates/budget",
    "crates/render-cpu",
    "crates/render-gpu",
    "crates/accel",
    "crates/scene",
    "crates/experiment/src/bench/source.rs",
    "crates/experiment/src/bench/screen_quality.rs",
    "crates/experiment/src/calibrate_motion.rs",
    "Cargo.lock",
];

/// What a revision ends with when the sources it stands for have uncommitted changes.
pub const DIRTY: &str = "-dirty";

/// The git revision of the working tree the command runs in (with `-dirty` when it has
/// uncommitted changes), or the version this binary was built as when there is no git.
pub fn git_revision() -> String {
    revision_in(Path::new("."), &[])
}

/// The last git revision that changed [`REFERENCE_SOURCES`] in the working tree the command
/// runs in (with `-dirty` when they have uncommitted changes), or the version this binary was
/// built as when there is no git: what reference pictures are kept by, so that a new
/// revision of the controllers reuses the references an earlier one rendered (on the CPU
/// renderer at 640x360 about 400 to 500 s per scene of the suite).
pub fn reference_revision() -> String {
    revision_in(Path::new("."), &REFERENCE_SOURCES)
}

/// The last revision of the repository holding `dir` that changed any of `sources` (paths
/// from the repository's root; none: the whole tree), with `-dirty` when any of them has
/// uncommitted changes; without git, the version this binary was built as.
pub fn revision_in(dir: &Path, sources: &[&str]) -> String {
    let git = |args: &[&str]| {
        let pathspecs = sources.iter().map(|p| format!(":(top){p}"));
        Command::new("git")
            .arg("-C")
            .arg(dir)
            .args(args)
            .arg("--")
            .args(pathspecs)
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    match git(&["log", "-1", "--format=%H"]).filter(|rev| !rev.is_empty()) {
        Some(rev) => {
            let short = &rev[..rev.len().min(12)];
            let dirty = git(&["status", "--porcelain", "--untracked-files=no"])
                .is_some_and(|s| !s.is_empty());
            if dirty {
                format!("{short}{DIRTY}")
            } else {
                short.to_string()
            }
        }
        None => format!("v{}", env!("CARGO_PKG_VERSION")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs git in `dir`, failing the test on an error.
    fn git(dir: &Path, args: &[&str]) {
        let status = Command::new("git")
            .arg("-C")
            .arg(dir)
            .args(["-c", "user.name=test", "-c", "user.email=test@example.com"])
            .args(args)
            .status()
            .unwrap();
        assert!(status.success(), "git {args:?}");
    }

    /// Writes `text` to `path` under `dir` and commits it.
    fn commit(dir: &Path, path: &str, text: &str) {
        let file = dir.join(path);
        std::fs::create_dir_all(file.parent().unwrap()).unwrap();
        std::fs::write(file, text).unwrap();
        git(dir, &["add", "."]);
        git(dir, &["commit", "-q", "-m", path]);
    }

    #[test]
    fn the_reference_revision_moves_only_with_the_sources_of_the_pictures() {
        if Command::new("git").arg("--version").output().is_err() {
            eprintln!("SKIPPED: no git on this machine, so no revisions to tell apart");
            return;
        }
        let tmp = tempfile::Builder::new()
            .prefix("steadyray-revision-")
            .tempdir()
            .unwrap();
        let dir = tmp.path();
        git(dir, &["init", "-q"]);
        commit(dir, "crates/render-cpu/src/lib.rs", "a");
        let rendered = revision_in(dir, &REFERENCE_SOURCES);
        assert!(!rendered.starts_with('v'), "{rendered}");
        commit(dir, "crates/control/src/lib.rs", "a controller");
        assert_eq!(revision_in(dir, &REFERENCE_SOURCES), rendered);
        assert_ne!(revision_in(dir, &[]), rendered);
        // From a folder inside the tree, the sources are still the root's.
        assert_eq!(
            revision_in(&dir.join("crates"), &REFERENCE_SOURCES),
            rendered
        );

        std::fs::write(dir.join("crates/control/src/lib.rs"), "edited").unwrap();
        assert_eq!(revision_in(dir, &REFERENCE_SOURCES), rendered);
        std::fs::write(dir.join("crates/render-cpu/src/lib.rs"), "edited").unwrap();
        assert_eq!(
            revision_in(dir, &REFERENCE_SOURCES),
            format!("{rendered}-dirty")
        );
        commit(dir, "crates/render-cpu/src/lib.rs", "b");
        let renderer_changed = revision_in(dir, &REFERENCE_SOURCES);
        assert_ne!(renderer_changed, rendered);
        assert_eq!(renderer_changed, revision_in(dir, &[]));
    }

    #[test]
    fn the_reference_sources_hold_every_crate_the_renderers_build_on() {
        // A crate the renderers depend on that the list misses would change the pictures
        // without moving the revision they are kept by, and a stale reference be reused.
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let listed: Vec<&str> = REFERENCE_SOURCES
            .iter()
            .filter_map(|p| p.strip_prefix("crates/"))
            .filter(|c| !c.contains('/'))
            .collect();
        assert!(listed.contains(&"render-cpu"), "{listed:?}");
        for dir in &listed {
            let path = root.join("crates").join(dir).join("Cargo.toml");
            let text = std::fs::read_to_string(&path).unwrap();
            let manifest: toml::Table = text.parse().unwrap();
            let Some(deps) = manifest.get("dependencies").and_then(|d| d.as_table()) else {
                continue;
            };
            for name in deps.keys() {
                if let Some(own) = name.strip_prefix("steadyray-") {
                    assert!(
                        listed.contains(&own),
                        "crates/{dir} depends on {name}: add crates/{own} to REFERENCE_SOURCES"
                    );
                }
            }
        }
    }
}
