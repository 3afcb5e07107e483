//! Assembles a [`Mesh`]: collects triangles per material, then lays indices out grouped by
//! material so the renderer issues one draw per material.

use super::mesh::{Aabb, DrawRange, LoadStats, Material, Mesh, Vertex};
use glam::{Quat, Vec3};

#[derive(Default)]
pub struct MeshBuilder {
    vertices: Vec<Vertex>,
    materials: Vec<Material>,
    /// Per material: flat triangle index list (3 per triangle).
    triangles: Vec<Vec<u32>>,
    stats: LoadStats,
}

impl MeshBuilder {
    pub fn new() -> Self {
        Self::default()
    }

    pub fn add_material(&mut self, material: Material) -> usize {
        self.materials.push(material);
        self.triangles.push(Vec::new());
        self.materials.len() - 1
    }

    pub fn vertex_count(&self) -> usize {
        self.vertices.len()
    }

    pub fn push_vertex(&mut self, v: Vertex) -> u32 {
        // Vertex counts come from files held in memory, so they are far below u32::MAX.
        self.vertices.push(v);
        (self.vertices.len() - 1) as u32
    }

    /// Adds a triangle. `material` must come from [`Self::add_material`] and the indices from
    /// [`Self::push_vertex`]; both are internal invariants, not user input.
    pub fn push_triangle(&mut self, material: usize, tri: [u32; 3]) {
        debug_assert!(tri.iter().all(|&i| (i as usize) < self.vertices.len()));
        self.triangles[material].extend_from_slice(&tri);
    }

    /// Adds a planar convex polygon with one flat normal. The triangles are wound
    /// counter-clockwise seen from the side `normal` points to, whatever the corner order.
    pub fn add_flat_polygon(&mut self, material: usize, corners: &[Vec3], normal: Vec3) {
        let n = normal.normalize_or(Vec3::Y);
        let base = self.vertices.len() as u32;
        for &c in corners {
            self.push_vertex(Vertex::new(c, n, [0.0, 0.0]));
        }
        for k in 1..corners.len().saturating_sub(1) {
            let (a, b, c) = (corners[0], corners[k], corners[k + 1]);
            let tri = if (b - a).cross(c - a).dot(n) >= 0.0 {
                [base, base + k as u32, base + k as u32 + 1]
            } else {
                [base, base + k as u32 + 1, base + k as u32]
            };
            self.push_triangle(material, tri);
        }
    }

    /// Copies `mesh` in, transformed by `p * scale + offset` (uniform scale keeps normals).
    /// Its materials, counters and warnings come along.
    pub fn append(&mut self, mesh: &Mesh, scale: f32, offset: Vec3) {
        self.append_placed(mesh, scale, Quat::IDENTITY, offset, None);
    }

    /// Copies `mesh` in, placed at `rotation * (p * scale) + offset` (uniform scale: normals
    /// only rotate). With `albedo`, every material takes that colour and no texture.
    pub fn append_placed(
        &mut self,
        mesh: &Mesh,
        scale: f32,
        rotation: Quat,
        offset: Vec3,
        albedo: Option<[f32; 3]>,
    ) {
        let base = self.vertices.len() as u32;
        // Without a rotation the normals are copied bit for bit.
        let rotate = |v: Vec3| {
            if rotation == Quat::IDENTITY {
                v
            } else {
                rotation * v
            }
        };
        self.vertices.extend(mesh.vertices.iter().map(|v| Vertex {
            position: (rotate(v.pos() * scale) + offset).to_array(),
            normal: rotate(Vec3::from(v.normal)).to_array(),
            ..*v
        }));
        let first_material = self.materials.len();
        for m in &mesh.materials {
            let material = match albedo {
                Some(diffuse) => Material {
                    diffuse,
                    diffuse_texture: None,
                    ..m.clone()
                },
                None => m.clone(),
            };
            self.add_material(material);
        }
        for r in &mesh.ranges {
            let start = r.first_index as usize;
            let end = start + r.index_count as usize;
            let dst = &mut self.triangles[first_material + r.material];
            dst.extend(mesh.indices[start..end].iter().map(|&i| i + base));
        }
        self.stats.faces += mesh.stats.faces;
        self.stats.triangles += mesh.stats.triangles;
        self.stats.dropped_zero_area += mesh.stats.dropped_zero_area;
        self.stats.dropped_slivers += mesh.stats.dropped_slivers;
        self.stats
            .warnings
            .extend(mesh.stats.warnings.iter().cloned());
    }

    pub fn stats_mut(&mut self) -> &mut LoadStats {
        &mut self.stats
    }

    /// Lays out indices grouped by material, drops materials no triangle uses, and computes
    /// the bounds of the referenced vertices.
    pub fn build(self) -> Mesh {
        let mut indices = Vec::with_capacity(self.triangles.iter().map(Vec::len).sum());
        let mut ranges = Vec::new();
        let mut materials = Vec::new();
        for (material, tris) in self.materials.into_iter().zip(self.triangles) {
            if tris.is_empty() {
                continue;
            }
            ranges.push(DrawRange {
                material: materials.len(),
                first_index: indices.len() as u32,
                index_count: tris.len() as u32,
            });
            materials.push(material);
            indices.extend_from_slice(&tris);
        }
        let bounds = Aabb::from_points(indices.iter().map(|&i| self.vertices[i as usize].pos()));
        Mesh {
            vertices: self.vertices,
            indices,
            ranges,
            materials,
            bounds,
            stats: self.stats,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygon_winding_follows_normal() {
        let mut b = MeshBuilder::new();
        let m = b.add_material(Material::default_material());
        // Corners listed clockwise seen from +y; the builder must still face +y.
        let quad = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, -1.0),
            Vec3::new(1.0, 0.0, -1.0),
            Vec3::new(1.0, 0.0, 0.0),
        ];
        b.add_flat_polygon(m, &quad, Vec3::Y);
        let mesh = b.build();
        assert_eq!(mesh.triangle_count(), 2);
        for t in 0..2 {
            let [a, b, c] = mesh.triangle(t);
            assert!((b - a).cross(c - a).dot(Vec3::Y) > 0.0);
        }
    }

    #[test]
    fn ranges_group_by_material_and_skip_unused() {
        let mut b = MeshBuilder::new();
        let red = b.add_material(Material::colour("red", [1.0, 0.0, 0.0]));
        let _unused = b.add_material(Material::colour("unused", [0.0, 0.0, 1.0]));
        let white = b.add_material(Material::colour("white", [1.0; 3]));
        let tri = [Vec3::ZERO, Vec3::X, Vec3::Y];
        b.add_flat_polygon(white, &tri, Vec3::Z);
        b.add_flat_polygon(red, &tri, Vec3::Z);
        b.add_flat_polygon(white, &tri, Vec3::Z);
        let mesh = b.build();
        let names: Vec<_> = mesh.materials.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(names, ["red", "white"]);
        assert_eq!(
            mesh.ranges,
            [
                DrawRange {
                    material: 0,
                    first_index: 0,
                    index_count: 3
                },
                DrawRange {
                    material: 1,
                    first_index: 3,
                    index_count: 6
                },
            ]
        );
        assert_eq!(mesh.material_of_triangle(2), Some(1));
    }
}
