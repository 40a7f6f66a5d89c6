//! glTF 2.0 import (`.gltf` with its buffers, or binary `.glb`): the triangles of every mesh
//! instanced by the nodes of the default scene (else the first scene), placed by the nodes'
//! transforms (each node's matrix times its parent's), grouped by the glTF material of their
//! primitives, and the file's materials mapped onto the Whitted model (see [`map_material`]).

use crate::Material;
use glam::{Mat4, Vec3};
use gltf::mesh::Mode;
use std::path::Path;

/// Triangles of one glTF material (or of primitives without one, `material == None`).
pub(crate) struct GltfGroup {
    /// Index into [`GltfData::materials`]; `None` for primitives with no material.
    pub material: Option<usize>,
    pub positions: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
}

/// What a glTF file holds for a scene: its materials (label, mapped material) and its
/// triangles grouped by material, groups in order of first use.
pub(crate) struct GltfData {
    /// The glTF material's name, or its index when it has none (or shares its name with an
    /// earlier material of the file), and the mapped material; in the file's order.
    pub materials: Vec<(String, Material)>,
    pub groups: Vec<GltfGroup>,
}

/// The IOR of a transmissive material that gives none (KHR_materials_ior's default).
pub const DEFAULT_IOR: f32 = 1.5;

/// The Whitted material of a glTF material (textures are ignored), with the base colour
/// factor's RGB (clamped to be non-negative) as the colour:
/// - KHR_materials_transmission factor > 0.5: dielectric, `ior` from KHR_materials_ior
///   (1.5 when absent, or when it is below 1 or not finite), `tint` = base colour;
/// - else metallic factor >= 0.5: mirror, `reflectance` = base colour;
/// - else diffuse, `albedo` = base colour, no checker.
pub(crate) fn map_material(m: &gltf::Material) -> Material {
    let pbr = m.pbr_metallic_roughness();
    let [r, g, b, _] = pbr.base_color_factor();
    let colour = Vec3::new(r, g, b).max(Vec3::ZERO);
    let colour = if colour.is_finite() {
        colour
    } else {
        Vec3::ONE
    };
    let transmission = m.transmission().map_or(0.0, |t| t.transmission_factor());
    if transmission > 0.5 {
        let ior = m
            .ior()
            .filter(|i| i.is_finite() && *i >= 1.0)
            .unwrap_or(DEFAULT_IOR);
        Material::Dielectric { ior, tint: colour }
    } else if pbr.metallic_factor() >= 0.5 {
        Material::Mirror {
            reflectance: colour,
        }
    } else {
        Material::Diffuse {
            albedo: colour,
            checker: None,
        }
    }
}

/// Positions and triangles (0-based, into the group's positions) of the glTF file at
/// `path`, in the file's world space, grouped by material. Primitives that are not triangle
/// lists (points, lines, strips, fans) are refused, as are indices past their primitive's
/// vertices.
pub(crate) fn read_gltf(path: &Path) -> Result<GltfData, String> {
    let gltf = gltf::Gltf::open(path).map_err(|e| e.to_string())?;
    let buffers = gltf::import_buffers(&gltf.document, path.parent(), gltf.blob.clone())
        .map_err(|e| format!("cannot load buffers: {e}"))?;
    let document = &gltf.document;
    let scene = document
        .default_scene()
        .or_else(|| document.scenes().next())
        .ok_or("the file has no scene")?;
    let mut materials: Vec<(String, Material)> = Vec::new();
    for (i, m) in document.materials().enumerate() {
        let label = match m.name() {
            Some(n) if !n.is_empty() && !materials.iter().any(|(l, _)| l == n) => n.to_owned(),
            _ => i.to_string(),
        };
        materials.push((label, map_material(&m)));
    }
    let mut groups: Vec<GltfGroup> = Vec::new();
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
                let material = primitive.material().index();
                let g = match groups.iter().position(|g| g.material == material) {
                    Some(g) => g,
                    None => {
                        groups.push(GltfGroup {
                            material,
                            positions: Vec::new(),
                            triangles: Vec::new(),
                        });
                        groups.len() - 1
                    }
                };
                let group = &mut groups[g];
                let reader = primitive.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
                let Some(points) = reader.read_positions() else {
                    return Err(format!(
                        "mesh {} ({name}) primitive {p} has no positions",
                        mesh.index()
                    ));
                };
                let base = group.positions.len() as u32;
                let before = group.positions.len();
                group
                    .positions
                    .extend(points.map(|q| world.transform_point3(Vec3::from(q))));
                let count = (group.positions.len() - before) as u32;
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
                group.triangles.extend(
                    indices
                        .chunks_exact(3)
                        .map(|t| [t[0], t[1], t[2]].map(|i| base + i)),
                );
            }
        }
        pending.extend(node.children().map(|c| (c, world)));
    }
    Ok(GltfData { materials, groups })
}
