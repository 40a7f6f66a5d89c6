//! `raybench --dump-rays FILE`: the triangles and the exact rays `raybench` traced, with
//! their t ranges and the closest hits it found, in a flat little-endian binary file, so
//! that another ray tracer can trace the very same rays (`scripts/embree/` does, with
//! Embree) and its hits can be checked against these.
//!
//! The format (version 1; every number little-endian):
//!
//! | bytes | what |
//! |---|---|
//! | 8 | magic `SRAYDUMP` |
//! | 4 | u32 version, 1 |
//! | 4 | u32 N, the triangle count |
//! | 4 | u32 S, the ray set count |
//! | 4 | u32 0, reserved |
//! | 36 N | the triangles in raybench's order (the hits' indices): corners a, b, c, each f32 x, y, z |
//!
//! then S ray sets, each:
//!
//! | bytes | what |
//! |---|---|
//! | 16 | its name in ASCII, NUL-padded (`primary`, `bounce`) |
//! | 8 | u64 M, its ray count |
//! | 40 M | M rays (below) |
//!
//! A ray is ten 4-byte fields: origin f32 x, y, z; direction f32 x, y, z (not normalised in
//! general); f32 t_min and t_max, the open interval (t_min, t_max) on which a hit counts;
//! the closest hit's f32 t (NaN for a miss) and u32 triangle index (0xFFFF_FFFF for a miss).

use anyhow::{Context, bail};
use bytemuck::{Pod, Zeroable};
use glam::{Vec3, Vec3A};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// The first bytes of a ray dump.
pub const MAGIC: &[u8; 8] = b"SRAYDUMP";
/// The format version this writes.
pub const VERSION: u32 = 1;
/// The triangle index of a miss.
pub const NO_HIT: u32 = u32::MAX;

/// One ray of a dump: the record of the format above.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct DumpRay {
    /// Where the ray starts.
    pub origin: [f32; 3],
    /// Its direction.
    pub dir: [f32; 3],
    /// The start of its t range.
    pub t_min: f32,
    /// The end of its t range.
    pub t_max: f32,
    /// The closest hit's t (NaN for a miss).
    pub hit_t: f32,
    /// The closest hit's triangle (`u32::MAX` for a miss).
    pub hit_triangle: u32,
}

impl DumpRay {
    /// The ray `origin + t·dir` on (t_min, t_max) and its closest hit (t, triangle), if any.
    pub fn new(
        origin: Vec3A,
        dir: Vec3A,
        (t_min, t_max): (f32, f32),
        hit: Option<(f32, u32)>,
    ) -> Self {
        let (hit_t, hit_triangle) = hit.unwrap_or((f32::NAN, NO_HIT));
        Self {
            origin: origin.to_array(),
            dir: dir.to_array(),
            t_min,
            t_max,
            hit_t,
            hit_triangle,
        }
    }
}

/// A named set of rays.
pub struct RaySet<'a> {
    /// At most 16 ASCII bytes.
    pub name: &'static str,
    /// The rays.
    pub rays: &'a [DumpRay],
}

/// Writes the triangles and ray sets to `path`, through a temporary file beside it that is
/// renamed into place only once complete (and removed on failure).
pub fn write(path: &Path, triangles: &[[Vec3; 3]], sets: &[RaySet]) -> anyhow::Result<()> {
    let mut tmp_name = path.as_os_str().to_owned();
    tmp_name.push(".partial");
    let tmp = PathBuf::from(tmp_name);
    let result = write_to(&tmp, triangles, sets).and_then(|()| {
        std::fs::rename(&tmp, path)
            .with_context(|| format!("cannot move {} to {}", tmp.display(), path.display()))
    });
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.with_context(|| format!("cannot write the ray dump {}", path.display()))
}

fn write_to(path: &Path, triangles: &[[Vec3; 3]], sets: &[RaySet]) -> anyhow::Result<()> {
    let count = |n: usize, what: &str| {
        u32::try_from(n).with_context(|| format!("{n} {what} are more than the format holds"))
    };
    let file = File::create(path).with_context(|| format!("cannot create {}", path.display()))?;
    let mut out = BufWriter::new(file);
    out.write_all(MAGIC)?;
    for word in [
        VERSION,
        count(triangles.len(), "triangles")?,
        count(sets.len(), "ray sets")?,
        0,
    ] {
        out.write_all(&word.to_le_bytes())?;
    }
    for corner in triangles.iter().flatten() {
        for value in corner.to_array() {
            out.write_all(&value.to_le_bytes())?;
        }
    }
    for set in sets {
        let mut name = [0u8; 16];
        if !set.name.is_ascii() || set.name.len() > name.len() {
            bail!("ray set name {:?} is not at most 16 ASCII bytes", set.name);
        }
        name[..set.name.len()].copy_from_slice(set.name.as_bytes());
        out.write_all(&name)?;
        out.write_all(&(set.rays.len() as u64).to_le_bytes())?;
        write_rays(&mut out, set.rays)?;
    }
    out.into_inner()
        .map_err(|e| e.into_error())?
        .sync_all()
        .context("cannot flush the file")
}

/// The records, each field little-endian.
fn write_rays(out: &mut impl Write, rays: &[DumpRay]) -> std::io::Result<()> {
    for ray in rays {
        for word in bytemuck::cast::<DumpRay, [u32; 10]>(*ray) {
            out.write_all(&word.to_le_bytes())?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A dump has the documented layout, byte for byte, and an unwritable path is an error
    /// that leaves nothing behind.
    #[test]
    fn layout_is_as_documented() {
        let tmp = tempfile::Builder::new()
            .prefix("steadyray-ray-dump-")
            .tempdir()
            .unwrap();
        let dir = tmp.path();
        let path = dir.join("rays.bin");
        let tri = [Vec3::new(1.0, 2.0, 3.0), Vec3::X, Vec3::Y];
        let hit = DumpRay::new(
            Vec3A::ZERO,
            Vec3A::NEG_Z,
            (1e-4, f32::INFINITY),
            Some((2.5, 0)),
        );
        let miss = DumpRay::new(Vec3A::ONE, Vec3A::X, (1e-4, 7.0), None);
        let sets = [
            RaySet {
                name: "primary",
                rays: &[hit, miss],
            },
            RaySet {
                name: "bounce",
                rays: &[],
            },
        ];
        write(&path, &[tri], &sets).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
        let float = |at: usize| f32::from_bits(word(at));
        assert_eq!(&bytes[..8], MAGIC);
        assert_eq!([word(8), word(12), word(16), word(20)], [1, 1, 2, 0]);
        assert_eq!(
            [float(24), float(28), float(32), float(36)],
            [1.0, 2.0, 3.0, 1.0]
        );
        let set = 24 + 36;
        assert_eq!(&bytes[set..set + 8], b"primary\0");
        assert_eq!(
            u64::from_le_bytes(bytes[set + 16..set + 24].try_into().unwrap()),
            2
        );
        let first = set + 24;
        assert_eq!(float(first + 20), -1.0);
        assert_eq!(
            [float(first + 24), float(first + 28)],
            [1e-4, f32::INFINITY]
        );
        assert_eq!((float(first + 32), word(first + 36)), (2.5, 0));
        let second = first + 40;
        assert!(float(second + 32).is_nan());
        assert_eq!(word(second + 36), NO_HIT);
        let bounce = second + 40;
        assert_eq!(&bytes[bounce..bounce + 7], b"bounce\0");
        assert_eq!(bytes.len(), bounce + 24);
        assert!(!dir.join("rays.bin.partial").exists());

        let nowhere = dir.join("no such folder").join("rays.bin");
        let err = write(&nowhere, &[tri], &sets).unwrap_err();
        assert!(format!("{err:#}").contains("cannot create"), "{err:#}");
    }
}
