//! Mesh import: Wavefront OBJ files (positions and faces) and glTF 2.0 files (`.gltf`,
//! `.glb`: meshes placed by their nodes, split by glTF material) turned into world-space
//! [`TriangleMesh`]es, and the checks every mesh goes through (also inline meshes written in a
//! scene file): finite vertices, indices in range, degenerate triangles dropped, not empty.

use crate::{Material, Transform, TriangleMesh};
use glam::Vec3;
use std::path::{Path, PathBuf};

/// A mesh ready for a scene, with what the import had to leave out.
#[derive(Clone, Debug, PartialEq)]
pub struct ImportedMesh {
    /// The mesh, in its own (model) space.
    pub mesh: TriangleMesh,
    /// Triangles dropped because their area is zero (repeated or collinear corners).
    pub degenerate_dropped: usize,
}

/// What is wrong with a mesh's data, wherever it came from.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MeshProblem {
    /// A vertex position is NaN or infinite.
    #[error("vertex {vertex} is not finite: {position:?}")]
    NonFinite {
        /// The vertex's index.
        vertex: usize,
        /// Its position as read.
        position: [f32; 3],
    },
    /// A triangle names a vertex that does not exist.
    #[error("triangle {triangle} refers to vertex {index}, but there are only {vertices} vertices")]
    IndexOutOfRange {
        /// The triangle's index.
        triangle: usize,
        /// The vertex index it names.
        index: u32,
        /// How many vertices there are.
        vertices: usize,
    },
    /// The mesh has no triangles at all.
    #[error("mesh has no triangles")]
    Empty,
    /// Every triangle has zero area (the count is the field).
    #[error("all {0} triangles are degenerate (zero area)")]
    AllDegenerate(usize),
}

/// Why a mesh file could not be imported; every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum MeshImportError {
    /// The file could not be read.
    #[error("mesh file {}: cannot read: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The read error.
        source: std::io::Error,
    },
    /// The file's extension is none of `.obj`, `.gltf`, `.glb`.
    #[error("mesh file {}: unsupported format (only .obj, .gltf and .glb are supported)", path.display())]
    Unsupported {
        /// The file.
        path: PathBuf,
    },
    /// The glTF reader refused the file.
    #[error("mesh file {}: malformed glTF: {reason}", path.display())]
    Gltf {
        /// The file.
        path: PathBuf,
        /// The glTF reader's message.
        reason: String,
    },
    /// The OBJ reader refused the file.
    #[error("mesh file {}: malformed OBJ: {reason}", path.display())]
    Obj {
        /// The file.
        path: PathBuf,
        /// The OBJ reader's error.
        reason: tobj::LoadError,
    },
    /// The file was read, but its mesh is unusable.
    #[error("mesh file {}: {problem}", path.display())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// What is wrong with its mesh.
        problem: MeshProblem,
    },
}

/// One material's share of a mesh file, ready for a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshPart {
    /// Index into [`ImportedParts::materials`]; `None` for triangles without a material
    /// (all of an OBJ file; glTF primitives that name no material).
    pub material: Option<usize>,
    /// This material's triangles, in the mesh's own (model) space.
    pub mesh: TriangleMesh,
}

/// A mesh file split by material: what [`import_mesh_parts`] returns.
#[derive(Clone, Debug, PartialEq)]
pub struct ImportedParts {
    /// The file's materials, in the file's order, each with a label (the glTF material's
    /// name, or its index when it has none or repeats an earlier name) and its mapping onto
    /// the Whitted model (see `docs/scene-format.md`). Empty for OBJ files.
    pub materials: Vec<(String, Material)>,
    /// One part per material used, in order of first use; never empty.
    pub parts: Vec<MeshPart>,
    /// Triangles dropped because their area is zero, over all parts (a part whose
    /// triangles are all degenerate is dropped whole while another part is left).
    pub degenerate_dropped: usize,
}

/// Reads the mesh file at `path` (OBJ or glTF, chosen by the extension) and places it
/// with `transform`, all of its triangles merged into one mesh (the file's materials are
/// not read).
pub fn import_mesh(path: &Path, transform: &Transform) -> Result<ImportedMesh, MeshImportError> {
    let (_, groups) = read_file(path)?;
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for (_, p, t) in groups {
        let base = positions.len() as u32;
        positions.extend(p);
        triangles.extend(t.into_iter().map(|tri| tri.map(|i| base + i)));
    }
    build_mesh(positions, triangles, transform).map_err(|problem| MeshImportError::Invalid {
        path: path.to_owned(),
        problem,
    })
}

/// As [`import_mesh`], but split by material: one part per glTF material (with the
/// materials themselves), or a single part without a material for an OBJ file.
pub fn import_mesh_parts(
    path: &Path,
    transform: &Transform,
) -> Result<ImportedParts, MeshImportError> {
    let (materials, groups) = read_file(path)?;
    let invalid = |problem| MeshImportError::Invalid {
        path: path.to_owned(),
        problem,
    };
    if groups.len() <= 1 {
        let (material, p, t) = groups
            .into_iter()
            .next()
            .unwrap_or((None, Vec::new(), Vec::new()));
        let m = build_mesh(p, t, transform).map_err(invalid)?;
        return Ok(ImportedParts {
            materials,
            parts: vec![MeshPart {
                material,
                mesh: m.mesh,
            }],
            degenerate_dropped: m.degenerate_dropped,
        });
    }
    let mut parts = Vec::new();
    let mut dropped = 0;
    for (material, p, t) in groups {
        match build_mesh(p, t, transform) {
            Ok(m) => {
                dropped += m.degenerate_dropped;
                parts.push(MeshPart {
                    material,
                    mesh: m.mesh,
                });
            }
            Err(MeshProblem::AllDegenerate(n)) => dropped += n,
            Err(MeshProblem::Empty) => {}
            Err(problem) => return Err(invalid(problem)),
        }
    }
    if parts.is_empty() {
        return Err(invalid(if dropped > 0 {
            MeshProblem::AllDegenerate(dropped)
        } else {
            MeshProblem::Empty
        }));
    }
    Ok(ImportedParts {
        materials,
        parts,
        degenerate_dropped: dropped,
    })
}

/// Raw triangle groups of a mesh file (each with its material, if any) and its materials.
type Groups = Vec<(Option<usize>, Vec<Vec3>, Vec<[u32; 3]>)>;

fn read_file(path: &Path) -> Result<(Vec<(String, Material)>, Groups), MeshImportError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("obj") => {
            let text = std::fs::read_to_string(path).map_err(|source| MeshImportError::Read {
                path: path.to_owned(),
                source,
            })?;
            let (p, t) = parse_obj(&text).map_err(|reason| MeshImportError::Obj {
                path: path.to_owned(),
                reason,
            })?;
            Ok((Vec::new(), vec![(None, p, t)]))
        }
        Some("gltf" | "glb") => {
            if let Err(source) = std::fs::metadata(path) {
                return Err(MeshImportError::Read {
                    path: path.to_owned(),
                    source,
                });
            }
            let data =
                crate::gltf_import::read_gltf(path).map_err(|reason| MeshImportError::Gltf {
                    path: path.to_owned(),
                    reason,
                })?;
            let groups = data
                .groups
                .into_iter()
                .map(|g| (g.material, g.positions, g.triangles))
                .collect();
            Ok((data.materials, groups))
        }
        _ => Err(MeshImportError::Unsupported {
            path: path.to_owned(),
        }),
    }
}

/// Whether `path` names a glTF file (`.gltf` or `.glb`, any case), whose materials are read.
pub fn is_gltf_path(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"))
}

/// Positions and triangles of OBJ text, all objects and groups merged, polygons fanned into
/// triangles. Only `v` and `f` records are read (texture coordinates, normals and materials
/// are not part of the scene model); this also keeps tobj away from their index arithmetic.
fn parse_obj(text: &str) -> Result<(Vec<Vec3>, Vec<[u32; 3]>), tobj::LoadError> {
    let mut reduced = String::with_capacity(text.len());
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                reduced.push_str(line.trim());
                reduced.push('\n');
            }
            Some("f") => {
                reduced.push('f');
                for w in words {
                    reduced.push(' ');
                    reduced.push_str(w.split('/').next().unwrap_or(w));
                }
                reduced.push('\n');
            }
            _ => {}
        }
    }
    let (models, _) = tobj::load_obj_buf(&mut reduced.as_bytes(), &tobj::GPU_LOAD_OPTIONS, |_| {
        Err(tobj::LoadError::GenericFailure)
    })?;
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for model in models {
        let base = positions.len() as u32;
        let m = model.mesh;
        positions.extend(
            m.positions
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2])),
        );
        triangles.extend(
            m.indices
                .chunks_exact(3)
                .map(|t| [base + t[0], base + t[1], base + t[2]]),
        );
    }
    Ok((positions, triangles))
}

/// Checks and places raw mesh data: every vertex finite (before and after `transform`), every
/// index in range; degenerate triangles are dropped and counted; a mesh with no triangle
/// left is an error. With the identity transform the positions are kept bit for bit.
pub fn build_mesh(
    positions: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    transform: &Transform,
) -> Result<ImportedMesh, MeshProblem> {
    let check_finite = |positions: &[Vec3]| match positions.iter().position(|p| !p.is_finite()) {
        Some(vertex) => Err(MeshProblem::NonFinite {
            vertex,
            position: positions[vertex].to_array(),
        }),
        None => Ok(()),
    };
    check_finite(&positions)?;
    let positions = if transform.is_identity() {
        positions
    } else {
        let placed: Vec<Vec3> = positions.iter().map(|&p| transform.apply(p)).collect();
        check_finite(&placed)?;
        placed
    };
    if triangles.is_empty() {
        return Err(MeshProblem::Empty);
    }
    let total = triangles.len();
    let mut kept = Vec::with_capacity(total);
    for (i, tri) in triangles.into_iter().enumerate() {
        if let Some(&index) = tri.iter().find(|&&v| v as usize >= positions.len()) {
            return Err(MeshProblem::IndexOutOfRange {
                triangle: i,
                index,
                vertices: positions.len(),
            });
        }
        let [a, b, c] = tri.map(|v| positions[v as usize]);
        if (b - a).cross(c - a).length_squared() > 0.0 {
            kept.push(tri);
        }
    }
    if kept.is_empty() {
        return Err(MeshProblem::AllDegenerate(total));
    }
    Ok(ImportedMesh {
        degenerate_dropped: total - kept.len(),
        mesh: TriangleMesh {
            positions,
            triangles: kept,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degenerate_triangles_are_dropped_and_counted() {
        let positions = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(2.0, 0.0, 0.0)];
        let tris = vec![[0, 1, 2], [0, 1, 3], [2, 2, 1]];
        let m = build_mesh(positions, tris, &Transform::default()).unwrap();
        assert_eq!(m.mesh.triangles, vec![[0, 1, 2]]);
        assert_eq!(m.degenerate_dropped, 2);
    }

    #[test]
    fn bad_meshes_are_errors() {
        let id = Transform::default();
        let e = build_mesh(vec![Vec3::ZERO], vec![[0, 0, 5]], &id).unwrap_err();
        assert!(matches!(e, MeshProblem::IndexOutOfRange { index: 5, .. }));
        let e = build_mesh(vec![Vec3::NAN], vec![[0, 0, 0]], &id).unwrap_err();
        assert!(matches!(e, MeshProblem::NonFinite { vertex: 0, .. }));
        assert_eq!(
            build_mesh(vec![Vec3::ZERO], vec![], &id).unwrap_err(),
            MeshProblem::Empty
        );
        assert_eq!(
            build_mesh(vec![Vec3::ZERO], vec![[0, 0, 0]], &id).unwrap_err(),
            MeshProblem::AllDegenerate(1)
        );
    }

    #[test]
    fn obj_faces_ignore_texture_and_normal_indices() {
        let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n\
                   f 1/1/1 2/1/1 3/1/1 4/1/1\n";
        let (p, t) = parse_obj(obj).unwrap();
        assert_eq!(p.len(), 4);
        assert_eq!(t.len(), 2);
    }
}
