//! `bench --references DIR`: the references of the world at display times, kept on disk and
//! shared by every bench of the same set-up.
//!
//! Under the real clock the screen is compared with a reference of the world at each sampled
//! refresh, and the world's times are the display's refresh times: every bench of one scene
//! on one display at one size needs the same references, whatever its controller. Rendering
//! them is most of such a bench's time (on the CPU renderer at 640x360, about 29 of a 3 s
//! run's 32 s), so a series of benches (the scene suite's cells) renders each once:
//!
//! ```text
//! DIR/<key digest>/key.json            what they are references of (StoreKey)
//! DIR/<key digest>/t<nanoseconds>.png  the world at that time: 8-bit sRGB, full scale
//! ```
//!
//! The folder of one set-up is named by a digest of its [`StoreKey`], so benches of other
//! scenes, sizes, renderers or renderer revisions keep theirs beside it. Each picture is written
//! under a temporary name and renamed, so benches on several machines can share `DIR`.

use super::displayed::time_key;
use super::video::encode_png;
use anyhow::{Context, Result, bail};
use serde::{Deserialize, Serialize};
use std::hash::Hasher;
use std::path::{Path, PathBuf};
use steadyray_quality::Rgb8Image;

/// What a store's references are of: a reference is reused only where all of this matches.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StoreKey {
    /// The scene's name.
    pub scene: String,
    /// A digest of the whole scene (its geometry, materials, lights and paths), so an edited
    /// scene file does not reuse the old one's references.
    pub scene_digest: String,
    /// The backend.
    pub backend: String,
    /// The device.
    pub device: String,
    /// Full-scale image size.
    pub resolution: [u32; 2],
    /// The reference's eye rays per pixel S.
    pub spp: f32,
    /// The reference's depth R.
    pub depth: u32,
    /// The last source revision that changed what they show
    /// ([`super::machine::reference_revision`]): a revision that changed only a controller
    /// reuses them.
    pub renderer_revision: String,
}

impl StoreKey {
    /// Whether references of this key may be kept and reused: not when the renderer's
    /// sources have uncommitted changes (two such runs could differ and still share a key).
    pub fn reusable(&self) -> bool {
        !self.renderer_revision.ends_with(super::machine::DIRTY)
    }
}

/// A hex digest (64-bit FNV-1a) of `text`: stable across runs, machines and Rust versions.
pub fn digest(text: &str) -> String {
    let mut hasher = fnv::FnvHasher::default();
    hasher.write(text.as_bytes());
    format!("{:016x}", hasher.finish())
}

/// The references of one set-up kept in a folder.
#[derive(Clone, Debug)]
pub struct ReferenceStore {
    folder: PathBuf,
    resolution: (u32, u32),
}

impl ReferenceStore {
    /// The store of `key`'s references under `dir`: created if new; an error if its folder
    /// holds the references of another set-up (a digest collision) or cannot be written.
    pub fn open(dir: &Path, key: &StoreKey) -> Result<Self> {
        let text = serde_json::to_string_pretty(key)? + "\n";
        let folder = dir.join(digest(&text));
        std::fs::create_dir_all(&folder).with_context(|| {
            format!(
                "--references: cannot create the folder {}",
                folder.display()
            )
        })?;
        let key_file = folder.join("key.json");
        match std::fs::read_to_string(&key_file) {
            Ok(held) => {
                let held: StoreKey = serde_json::from_str(&held).with_context(|| {
                    format!("--references: {} is not a store key", key_file.display())
                })?;
                if &held != key {
                    bail!(
                        "--references: {} holds the references of another set-up ({} on {}); \
                         remove it or name another folder",
                        folder.display(),
                        held.scene,
                        held.backend
                    );
                }
            }
            Err(_) => write_atomically(&key_file, text.as_bytes())?,
        }
        let [width, height] = key.resolution;
        Ok(Self {
            folder,
            resolution: (width, height),
        })
    }

    /// The folder holding this set-up's references.
    pub fn folder(&self) -> &Path {
        &self.folder
    }

    fn path(&self, t_s: f64) -> PathBuf {
        self.folder.join(format!("t{}.png", time_key(t_s)))
    }

    /// The reference of the world at `t_s`, if the store holds it; an error for a picture
    /// that cannot be read or is not of the set-up's size.
    pub fn load(&self, t_s: f64) -> Result<Option<Rgb8Image>> {
        let path = self.path(t_s);
        if !path.exists() {
            return Ok(None);
        }
        let image = image::open(&path)
            .with_context(|| format!("--references: cannot read {}", path.display()))?
            .to_rgb8();
        let (width, height) = image.dimensions();
        if (width, height) != self.resolution {
            bail!(
                "--references: {} is {width}x{height}, not {}x{}",
                path.display(),
                self.resolution.0,
                self.resolution.1
            );
        }
        Ok(Some(Rgb8Image::from_rgb(width, height, image.into_raw())?))
    }

    /// Keeps `picture` as the reference of the world at `t_s` (lossless PNG).
    pub fn save(&self, t_s: f64, picture: &Rgb8Image) -> Result<()> {
        write_atomically(&self.path(t_s), &encode_png(picture)?)
    }
}

/// Writes `bytes` to `path` under a name of this process's and renames it: readers see the
/// whole file or none.
fn write_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let temp = path.with_file_name(format!(".{name}.{}.partial", std::process::id()));
    std::fs::write(&temp, bytes)
        .with_context(|| format!("--references: cannot write {}", temp.display()))?;
    std::fs::rename(&temp, path)
        .with_context(|| format!("--references: cannot write {}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(scene: &str) -> StoreKey {
        StoreKey {
            scene: scene.into(),
            scene_digest: digest(scene),
            backend: "cpu".into(),
            device: "test".into(),
            resolution: [4, 2],
            spp: 16.0,
            depth: 16,
            renderer_revision: "abc".into(),
        }
    }

    /// A fresh temporary folder, removed when dropped; the tests open their store in `store`
    /// inside it, a folder not made yet.
    fn scratch(name: &str) -> tempfile::TempDir {
        tempfile::Builder::new()
            .prefix(&format!("steadyray-store-{name}-"))
            .tempdir()
            .unwrap()
    }

    fn picture(level: u8) -> Rgb8Image {
        Rgb8Image::from_fn(4, 2, |x, y| [level, x as u8, y as u8])
    }

    #[test]
    fn a_key_of_uncommitted_renderer_sources_is_not_reusable() {
        assert!(key("a").reusable());
        let dirty = StoreKey {
            renderer_revision: "abc-dirty".into(),
            ..key("a")
        };
        assert!(!dirty.reusable());
    }

    #[test]
    fn pictures_come_back_as_saved_and_set_ups_keep_folders_of_their_own() {
        let tmp = scratch("round-trip");
        let dir = tmp.path().join("store");
        let store = ReferenceStore::open(&dir, &key("a")).unwrap();
        assert_eq!(store.load(0.5).unwrap(), None);
        store.save(0.5, &picture(7)).unwrap();
        let reopened = ReferenceStore::open(&dir, &key("a")).unwrap();
        assert_eq!(reopened.load(0.5).unwrap(), Some(picture(7)));
        let other = ReferenceStore::open(&dir, &key("b")).unwrap();
        assert_ne!(other.folder(), store.folder());
        assert_eq!(other.load(0.5).unwrap(), None);
    }

    #[test]
    fn a_folder_of_another_set_up_or_a_picture_of_another_size_is_an_error() {
        let tmp = scratch("mismatch");
        let dir = tmp.path().join("store");
        let store = ReferenceStore::open(&dir, &key("a")).unwrap();
        let held = serde_json::to_string(&key("b")).unwrap();
        std::fs::write(store.folder().join("key.json"), held).unwrap();
        let err = ReferenceStore::open(&dir, &key("a")).unwrap_err();
        assert!(
            format!("{err:#}").contains("another set-up (b on cpu)"),
            "{err:#}"
        );
        let wrong = Rgb8Image::from_fn(2, 2, |_, _| [0; 3]);
        store.save(1.0, &wrong).unwrap();
        let err = store.load(1.0).unwrap_err();
        assert!(format!("{err:#}").contains("is 2x2, not 4x2"), "{err:#}");
    }
}
