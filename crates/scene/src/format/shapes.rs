//! Materials, shapes, meshes and their copies and transforms.

use super::*;

impl Cx<'_> {
    pub(super) fn material(&self, raw: &Spanned<RawMaterial>) -> Result<Material, SceneError> {
        let r = raw.get_ref();
        let label = &format!("material {:?}", r.name.get_ref());
        let keys = present_keys!(r, albedo, checker, reflectance, ior, tint, radiance);
        match r.kind.get_ref().as_str() {
            "diffuse" => {
                self.only_keys(label, "a diffuse material", &keys, &["albedo", "checker"])?;
                let albedo = self.colour(
                    label,
                    "albedo",
                    self.required(label, "albedo", &r.albedo, raw)?,
                )?;
                let checker = match &r.checker {
                    Some(c) => {
                        let c = c.get_ref();
                        Some(Checker {
                            size: self.positive(label, "checker.size", &c.size)?,
                            albedo_b: self.colour(label, "checker.albedo_b", &c.albedo_b)?,
                        })
                    }
                    None => None,
                };
                Ok(Material::Diffuse { albedo, checker })
            }
            "mirror" => {
                self.only_keys(label, "a mirror material", &keys, &["reflectance"])?;
                let reflectance = self.colour(
                    label,
                    "reflectance",
                    self.required(label, "reflectance", &r.reflectance, raw)?,
                )?;
                Ok(Material::Mirror { reflectance })
            }
            "dielectric" => {
                self.only_keys(label, "a dielectric material", &keys, &["ior", "tint"])?;
                let ior = self.positive(label, "ior", self.required(label, "ior", &r.ior, raw)?)?;
                let tint = match &r.tint {
                    Some(t) => self.colour(label, "tint", t)?,
                    None => Vec3::ONE,
                };
                Ok(Material::Dielectric { ior, tint })
            }
            "emissive" => {
                self.only_keys(label, "an emissive material", &keys, &["radiance"])?;
                let radiance = self.colour(
                    label,
                    "radiance",
                    self.required(label, "radiance", &r.radiance, raw)?,
                )?;
                Ok(Material::Emissive { radiance })
            }
            other => Err(self.invalid(
                r.kind.span(),
                format!(
                    "{label}: unknown material type {other:?} \
                     (expected \"diffuse\", \"mirror\", \"dielectric\" or \"emissive\")"
                ),
            )),
        }
    }

    pub(super) fn shape(
        &mut self,
        raw: &Spanned<RawShape>,
        name: &str,
    ) -> Result<Shape, SceneError> {
        let r = raw.get_ref();
        let label = &format!("shape {name:?}");
        let keys = r.present_keys();
        match r.kind.get_ref().as_str() {
            "sphere" => {
                self.only_keys(label, "a sphere", &keys, &["center", "radius"])?;
                let center = self.vec3(
                    label,
                    "center",
                    self.required(label, "center", &r.center, raw)?,
                )?;
                let radius = self.positive(
                    label,
                    "radius",
                    self.required(label, "radius", &r.radius, raw)?,
                )?;
                Ok(Shape::Sphere { center, radius })
            }
            "quad" => {
                self.only_keys(label, "a quad", &keys, &["corner", "edge_u", "edge_v"])?;
                let corner = self.vec3(
                    label,
                    "corner",
                    self.required(label, "corner", &r.corner, raw)?,
                )?;
                let eu = self.required(label, "edge_u", &r.edge_u, raw)?;
                let ev = self.required(label, "edge_v", &r.edge_v, raw)?;
                let edge_u = self.nonzero(label, "edge_u", eu)?;
                let edge_v = self.nonzero(label, "edge_v", ev)?;
                if edge_u.cross(edge_v).length() <= 1e-6 * edge_u.length() * edge_v.length() {
                    return Err(self.invalid(
                        ev.span(),
                        format!("{label}: edge_u {edge_u} and edge_v {edge_v} are parallel"),
                    ));
                }
                Ok(Shape::Quad {
                    corner,
                    edge_u,
                    edge_v,
                })
            }
            "plane" => {
                self.only_keys(label, "a plane", &keys, &["point", "normal"])?;
                let point = self.vec3(
                    label,
                    "point",
                    self.required(label, "point", &r.point, raw)?,
                )?;
                let normal = self.nonzero(
                    label,
                    "normal",
                    self.required(label, "normal", &r.normal, raw)?,
                )?;
                Ok(Shape::Plane {
                    point,
                    normal: unit(normal),
                })
            }
            "mesh" => {
                self.mesh_keys(label, &keys)?;
                self.mesh(raw, label)
            }
            other => Err(self.invalid(
                r.kind.span(),
                format!(
                    "{label}: unknown shape type {other:?} \
                     (expected \"sphere\", \"quad\", \"plane\" or \"mesh\")"
                ),
            )),
        }
    }

    pub(super) fn mesh_keys(
        &self,
        label: &str,
        keys: &[(&'static str, Range<usize>)],
    ) -> Result<(), SceneError> {
        self.only_keys(
            label,
            "a mesh",
            keys,
            &[
                "path",
                "positions",
                "triangles",
                "translate",
                "scale",
                "rotate_y_deg",
                "instances",
            ],
        )
    }

    /// The parts of a glTF mesh shape that names no `material`: each part's mesh with the
    /// index of its material among the file's (label, material) pairs.
    #[allow(clippy::type_complexity)]
    pub(super) fn gltf_parts(
        &mut self,
        raw: &Spanned<RawShape>,
        name: &str,
    ) -> Result<(Vec<(String, Material)>, Vec<(crate::TriangleMesh, usize)>), SceneError> {
        let r = raw.get_ref();
        let label = &format!("shape {name:?}");
        let keys = r.present_keys();
        self.mesh_keys(label, &keys)?;
        let transform = self.mesh_transform(r, label)?;
        let Some(path) = &r.path else {
            return Err(self.invalid(raw.span(), format!("{label}: missing `path`")));
        };
        let file = match self.base_dir {
            Some(dir) => dir.join(path.get_ref()),
            None => Path::new(path.get_ref()).to_owned(),
        };
        let imported =
            mesh_import::import_mesh_parts(&file, &Transform::IDENTITY).map_err(|e| {
                self.err(
                    path.span(),
                    SceneErrorKind::Mesh,
                    format!("{label}: mesh {:?}: {e}", path.get_ref()),
                )
            })?;
        let mut parts = Vec::with_capacity(imported.parts.len());
        let mut kept = 0;
        for part in imported.parts {
            self.check_placed(&part.mesh, &transform, path, label)?;
            kept += part.mesh.triangles.len();
            match part.material {
                Some(m) => parts.push((part.mesh, m)),
                None => {
                    return Err(self.err(
                        path.span(),
                        SceneErrorKind::Mesh,
                        format!(
                            "{label}: mesh {:?}: {} triangles belong to glTF primitives with \
                             no material; give the shape a `material` (it then applies to the \
                             whole file)",
                            path.get_ref(),
                            part.mesh.triangles.len()
                        ),
                    ));
                }
            }
        }
        if imported.degenerate_dropped > 0 {
            let line = line_of(self.text, raw.span().start);
            self.notes.push(format!(
                "{}:{line}: {label}: dropped {} degenerate (zero-area) triangles, kept {kept}",
                self.origin, imported.degenerate_dropped,
            ));
        }
        Ok((imported.materials, parts))
    }

    pub(super) fn mesh_transform(
        &self,
        r: &RawShape,
        label: &str,
    ) -> Result<Transform, SceneError> {
        self.transform(label, &r.translate, &r.rotate_y_deg, &r.scale)
    }

    /// Checks that `placement` keeps every vertex of `mesh` finite; `at` is the key the
    /// mesh came from.
    pub(super) fn check_placed<T>(
        &self,
        mesh: &crate::TriangleMesh,
        placement: &Transform,
        at: &Spanned<T>,
        label: &str,
    ) -> Result<(), SceneError> {
        match mesh
            .positions
            .iter()
            .enumerate()
            .find(|(_, p)| !placement.apply(**p).is_finite())
        {
            Some((vertex, &p)) => Err(self.err(
                at.span(),
                SceneErrorKind::Mesh,
                format!(
                    "{label}: vertex {vertex} {p} is not finite once placed: {}",
                    placement.apply(p)
                ),
            )),
            None => Ok(()),
        }
    }

    pub(super) fn mesh(
        &mut self,
        raw: &Spanned<RawShape>,
        label: &str,
    ) -> Result<Shape, SceneError> {
        let r = raw.get_ref();
        let placement = self.mesh_transform(r, label)?;
        let imported = match (&r.path, &r.positions, &r.triangles) {
            (Some(path), None, None) => {
                let file = match self.base_dir {
                    Some(dir) => dir.join(path.get_ref()),
                    None => Path::new(path.get_ref()).to_owned(),
                };
                let imported =
                    mesh_import::import_mesh(&file, &Transform::IDENTITY).map_err(|e| {
                        self.err(
                            path.span(),
                            SceneErrorKind::Mesh,
                            format!("{label}: mesh {:?}: {e}", path.get_ref()),
                        )
                    })?;
                self.check_placed(&imported.mesh, &placement, path, label)?;
                imported
            }
            (None, Some(p), Some(t)) => {
                let positions = p.get_ref().iter().map(|&v| Vec3::from(v)).collect();
                let imported =
                    mesh_import::build_mesh(positions, t.get_ref().clone(), &Transform::IDENTITY)
                        .map_err(|e| {
                        self.err(p.span(), SceneErrorKind::Mesh, format!("{label}: {e}"))
                    })?;
                self.check_placed(&imported.mesh, &placement, p, label)?;
                imported
            }
            _ => {
                return Err(self.invalid(
                    raw.span(),
                    format!(
                        "{label}: a mesh needs either `path` (a mesh file) or both \
                         `positions` and `triangles`, not both"
                    ),
                ));
            }
        };
        if imported.degenerate_dropped > 0 {
            let line = line_of(self.text, raw.span().start);
            self.notes.push(format!(
                "{}:{line}: {label}: dropped {} degenerate (zero-area) triangles, kept {}",
                self.origin,
                imported.degenerate_dropped,
                imported.mesh.triangles.len()
            ));
        }
        Ok(Shape::Mesh {
            mesh: imported.mesh,
            placement,
            instances: self.instances(r, label)?,
        })
    }

    /// The `instances` of a mesh shape: none, or a non-empty list of transforms.
    pub(super) fn instances(
        &self,
        r: &RawShape,
        label: &str,
    ) -> Result<Vec<Transform>, SceneError> {
        let Some(list) = &r.instances else {
            return Ok(Vec::new());
        };
        if list.get_ref().is_empty() {
            return Err(self.invalid(
                list.span(),
                format!(
                    "{label}: instances must list at least one copy (leave the key out for a \
                     single copy)"
                ),
            ));
        }
        list.get_ref()
            .iter()
            .enumerate()
            .map(|(i, inst)| {
                let ir = inst.get_ref();
                self.transform(
                    &format!("{label}: instance {}", i + 1),
                    &ir.translate,
                    &ir.rotate_y_deg,
                    &ir.scale,
                )
            })
            .collect()
    }

    /// A transform from its optional parts, each finite, the scale also non-zero.
    pub(super) fn transform(
        &self,
        label: &str,
        translate: &Option<Spanned<V3>>,
        rotate_y_deg: &Option<Spanned<f32>>,
        scale: &Option<Spanned<Triple>>,
    ) -> Result<Transform, SceneError> {
        let mut transform = Transform::IDENTITY;
        if let Some(t) = translate {
            transform.translate = self.vec3(label, "translate", t)?;
        }
        if let Some(s) = scale {
            transform.scale = self.scale(label, s)?;
        }
        if let Some(a) = rotate_y_deg {
            transform.rotate_y_deg = self.number(label, "rotate_y_deg", a)?;
        }
        Ok(transform)
    }

    pub(super) fn scale(&self, label: &str, s: &Spanned<Triple>) -> Result<Vec3, SceneError> {
        let scale = Vec3::from(s.get_ref().0);
        if !scale.is_finite() || scale.cmpeq(Vec3::ZERO).any() {
            return Err(self.invalid(
                s.span(),
                format!("{label}: scale must be finite and non-zero, got {scale}"),
            ));
        }
        Ok(scale)
    }
}
