//! glTF 2.0 import (`.gltf` with its buffers, or binary `.glb`): the triangles of every mesh
//! instanced by the nodes of the default scene (else the first scene), placed by the nodes'
//! transforms (each node's matrix times its parent's), all merged into one mesh.

use glam::{Mat4, Vec3};
use gltf::mesh::Mode;
use std::path::Path;

/// Positions and triangles (0-based, into the positions) of the glTF file at `path`, in
/// the file's world space. Primitives that are not triangle lists (points, lines, strips,
/// fans) are refused, as are indices past their primitive's vertices.
pub(crate) fn read_gltf(path: &Path) -> Result<(Vec<Vec3>, Vec<[u32; 3]>), String> {
    let gltf = gltf::Gltf::open(path).map_err(|e| e.to_string())?;
    let buffers = gltf::import_buffers(&gltf.document, path.parent(), gltf.blob.clone())
        .map_err(|e| format!("cannot load buffers: {e}"))?;
    let document = &gltf.document;
    let scene = document
        .default_scene()
        .or_else(|| document.scenes().next())
        .ok_or("the file has no scene")?;
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let mut pending: Vec<(gltf::Node, Mat4)> = scene.nodes().map(|n| (n, Mat4::IDENTITY)).collect();
    while let Some((node, parent)) = pending.pop() {
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if let Some(mesh) = node.mesh() {
            for (p, primitive) in mesh.primitives().enumerate() {
                let name = mesh.name().unwrap_or("unnamed");
                if primitive.mode() != Mode::Triangles {
                    return Err(format!(
                        "mesh {} ({name}) primitive {p}: mode {:?} is not supported \
                         (only triangle lists)",
                        mesh.index(),
                        primitive.mode()
                    ));
                }
                let reader = primitive.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
                let Some(points) = reader.read_positions() else {
                    return Err(format!(
                        "mesh {} ({name}) primitive {p} has no positions",
                        mesh.index()
                    ));
                };
                let base = positions.len() as u32;
                let before = positions.len();
                positions.extend(points.map(|q| world.transform_point3(Vec3::from(q))));
                let count = (positions.len() - before) as u32;
                let indices: Vec<u32> = match reader.read_indices() {
                    Some(i) => i.into_u32().collect(),
                    None => (0..count).collect(),
                };
                if !indices.len().is_multiple_of(3) {
                    return Err(format!(
                        "mesh {} ({name}) primitive {p}: {} indices is not a whole number of \
                         triangles",
                        mesh.index(),
                        indices.len()
                    ));
                }
                if let Some(&bad) = indices.iter().find(|&&i| i >= count) {
                    return Err(format!(
                        "mesh {} ({name}) primitive {p}: index {bad} is out of range \
                         ({count} vertices)",
                        mesh.index()
                    ));
                }
                triangles.extend(
                    indices
                        .chunks_exact(3)
                        .map(|t| [t[0], t[1], t[2]].map(|i| base + i)),
                );
            }
        }
        pending.extend(node.children().map(|c| (c, world)));
    }
    Ok((positions, triangles))
}
