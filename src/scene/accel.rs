//! The scene's triangles in a BVH (obvhs's compressed-wide CWBVH; the choice between obvhs and
//! the `bvh` crate was made by rays per second, see docs/REFERENCE.md) with the two queries
//! the ground truth and the automatic framing need: the closest hit with its shading
//! attributes, and segment occlusion.

use super::mesh::Mesh;
use super::raycast::occlusion_span;
use glam::{Vec2, Vec3, Vec3A};
use obvhs::cwbvh::{builder::build_cwbvh_from_tris, CwBvh};
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;

/// A ray's closest hit.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    pub t: f32,
    pub position: Vec3,
    /// Triangle index in the mesh.
    pub triangle: usize,
    /// Barycentric weights of the triangle's second and third corners.
    pub uv: Vec2,
}

pub struct Accel {
    bvh: Option<CwBvh>,
    /// Triangles in BVH leaf order (no index lookup during traversal).
    triangles: Vec<Triangle>,
    /// Mesh triangle index of each entry of `triangles`.
    mesh_index: Vec<u32>,
}

impl Accel {
    /// Build over every triangle of `mesh` (obvhs's "medium" preset: its build time is a few
    /// hundred milliseconds for the shared models, small against a reference's tracing).
    pub fn new(mesh: &Mesh) -> Self {
        let tris = obvhs_triangles(mesh);
        if tris.is_empty() {
            return Self {
                bvh: None,
                triangles: Vec::new(),
                mesh_index: Vec::new(),
            };
        }
        let mut build_time = std::time::Duration::ZERO;
        let bvh = build_cwbvh_from_tris(&tris, BvhBuildParams::medium_build(), &mut build_time);
        let mesh_index = bvh.primitive_indices.clone();
        let triangles = mesh_index.iter().map(|&i| tris[i as usize]).collect();
        Self {
            bvh: Some(bvh),
            triangles,
            mesh_index,
        }
    }

    /// Closest hit along unit `dir` with t in (t_min, t_max), ignoring triangle `skip` (the
    /// surface the ray starts on: a flat triangle cannot be hit again by a ray leaving it).
    pub fn closest(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_min: f32,
        t_max: f32,
        skip: Option<usize>,
    ) -> Option<Hit> {
        let bvh = self.bvh.as_ref()?;
        let ray = Ray::new(origin.into(), dir.into(), t_min, t_max);
        let mut hit = RayHit::none();
        let skip = skip.map(|s| s as u32);
        let found = bvh.ray_traverse(ray, &mut hit, |ray, id| {
            if Some(self.mesh_index[id]) == skip {
                return f32::INFINITY;
            }
            self.triangles[id].intersect(ray)
        });
        if !found {
            return None;
        }
        let id = hit.primitive_id as usize;
        let tri = &self.triangles[id];
        let position = origin + dir * hit.t;
        Some(Hit {
            t: hit.t,
            position,
            triangle: self.mesh_index[id] as usize,
            uv: barycentric(tri, position.into()),
        })
    }

    /// Whether the segment `from → to` is blocked, ignoring triangle `skip` and the stretch
    /// at both ends that `Mesh::occluded` ignores (relative to the segment and to the float
    /// spacing of the endpoints: never a fixed world-space distance).
    pub fn occluded(&self, from: Vec3, to: Vec3, skip: Option<usize>) -> bool {
        let Some(bvh) = self.bvh.as_ref() else {
            return false;
        };
        let Some((len, offset)) = occlusion_span(from, to) else {
            return false;
        };
        let ray = Ray::new(
            from.into(),
            ((to - from) / len).into(),
            offset,
            len - offset,
        );
        let skip = skip.map(|s| s as u32);
        !bvh.ray_traverse_miss(ray, |ray, id| {
            if Some(self.mesh_index[id]) == skip {
                return f32::INFINITY;
            }
            self.triangles[id].intersect(ray)
        })
    }
}

/// Every triangle of `mesh` as obvhs builds over them, in the mesh's order (the CPU tracer's
/// CWBVH and the GPU's flattened BVH2 both start from these).
pub fn obvhs_triangles(mesh: &Mesh) -> Vec<Triangle> {
    (0..mesh.triangle_count())
        .map(|t| {
            let [a, b, c] = mesh.triangle(t);
            Triangle {
                v0: a.into(),
                v1: b.into(),
                v2: c.into(),
            }
        })
        .collect()
}

/// Barycentric weights (of v1, v2) of a point on the triangle's plane.
fn barycentric(tri: &Triangle, p: Vec3A) -> Vec2 {
    let e1 = tri.v1 - tri.v0;
    let e2 = tri.v2 - tri.v0;
    let w = p - tri.v0;
    let (d11, d12, d22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (dw1, dw2) = (w.dot(e1), w.dot(e2));
    let den = d11 * d22 - d12 * d12;
    if den <= 0.0 || !den.is_finite() {
        return Vec2::ZERO;
    }
    Vec2::new((d22 * dw1 - d12 * dw2) / den, (d11 * dw2 - d12 * dw1) / den)
        .clamp(Vec2::ZERO, Vec2::ONE)
}
