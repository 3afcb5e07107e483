//! CPU ray queries against a [`Mesh`], for reference values in tests (visibility, irradiance,
//! picking). Brute force over all triangles: O(triangles) per ray, fine for the procedural
//! scenes and a few rays on loaded models, not for full images of large models.

use super::mesh::Mesh;
use glam::Vec3;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the (normalised) ray direction.
    pub t: f32,
    pub position: Vec3,
    /// Geometric normal of the triangle, unit, flipped to face against the ray direction.
    pub normal: Vec3,
    /// Triangle index (`mesh.indices[3 * triangle..]`).
    pub triangle: usize,
}

/// Relative part of the offset `occluded` keeps from both ends of the segment.
pub const OCCLUSION_RELATIVE_OFFSET: f32 = 1e-4;
/// Offset in units of the endpoints' float spacing (`EPSILON × max |coordinate|`), so points
/// far from the origin, whose positions are only known to that precision, do not hit the
/// surface they lie on.
pub const OCCLUSION_ULPS: f32 = 8.0;

/// Length of the segment `from → to` and the stretch at each end an occlusion test ignores
/// (`OCCLUSION_RELATIVE_OFFSET × length + OCCLUSION_ULPS × EPSILON × max |coordinate|`); None
/// when the segment is empty, not finite, or too short to tell apart from its end surfaces.
pub fn occlusion_span(from: Vec3, to: Vec3) -> Option<(f32, f32)> {
    let len = (to - from).length();
    if len == 0.0 || !len.is_finite() {
        return None;
    }
    let magnitude = from.abs().max(to.abs()).max_element();
    let offset = OCCLUSION_RELATIVE_OFFSET * len + OCCLUSION_ULPS * f32::EPSILON * magnitude;
    (offset < 0.5 * len).then_some((len, offset))
}

/// Möller–Trumbore. Returns (t, u, v) in units of `dir` for t in (t_min, t_max).
/// Edges are inclusive (u, v ≥ 0, u + v ≤ 1) so a ray through a shared edge hits a triangle.
/// No epsilon on the determinant: degenerate triangles are removed at load, an exactly
/// parallel ray gives det = 0 (skipped), and a nearly parallel one gives barycentrics that
/// fail the range tests or a finite t.
fn intersect(o: Vec3, dir: Vec3, [a, b, c]: [Vec3; 3], t_min: f32, t_max: f32) -> Option<f32> {
    let e1 = b - a;
    let e2 = c - a;
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv = 1.0 / det;
    let s = o - a;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t > t_min && t < t_max).then_some(t)
}

impl Mesh {
    /// Closest hit with 0 < t < t_max along `dir` (normalised here; None if it is zero).
    pub fn raycast(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<Hit> {
        let dir = dir.try_normalize()?;
        let mut best: Option<(f32, usize)> = None;
        for tri in 0..self.triangle_count() {
            let limit = best.map_or(t_max, |(t, _)| t);
            if let Some(t) = intersect(origin, dir, self.triangle(tri), 0.0, limit) {
                best = Some((t, tri));
            }
        }
        let (t, triangle) = best?;
        let [a, b, c] = self.triangle(triangle);
        let n = (b - a).cross(c - a).normalize_or(-dir);
        Some(Hit {
            t,
            position: origin + dir * t,
            normal: if n.dot(dir) > 0.0 { -n } else { n },
            triangle,
        })
    }

    /// Whether any triangle blocks the segment `from → to`, ignoring a small stretch at both
    /// ends so that points on surfaces do not occlude themselves. The ignored stretch is
    /// `OCCLUSION_RELATIVE_OFFSET × length + OCCLUSION_ULPS × EPSILON × max |coordinate|`:
    /// relative to the segment and to the float precision of the endpoints, never a fixed
    /// world-space distance.
    pub fn occluded(&self, from: Vec3, to: Vec3) -> bool {
        let Some((len, offset)) = occlusion_span(from, to) else {
            return false;
        };
        let eps = offset / len;
        (0..self.triangle_count())
            .any(|tri| intersect(from, to - from, self.triangle(tri), eps, 1.0 - eps).is_some())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builder::MeshBuilder;
    use crate::scene::mesh::Material;

    fn unit_square_at_z0() -> Mesh {
        let mut b = MeshBuilder::new();
        let m = b.add_material(Material::default_material());
        let corners = [
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(-1.0, 1.0, 0.0),
        ];
        b.add_flat_polygon(m, &corners, Vec3::Z);
        b.build()
    }

    #[test]
    fn hits_and_normal_faces_the_ray() {
        let mesh = unit_square_at_z0();
        let h = mesh
            .raycast(Vec3::new(0.2, 0.3, 2.0), Vec3::NEG_Z * 5.0, 10.0)
            .unwrap();
        assert!((h.t - 2.0).abs() < 1e-6);
        assert!(h.position.abs_diff_eq(Vec3::new(0.2, 0.3, 0.0), 1e-6));
        assert_eq!(h.normal, Vec3::Z);
        let h = mesh
            .raycast(Vec3::new(0.2, 0.3, -2.0), Vec3::Z, 10.0)
            .unwrap();
        assert_eq!(h.normal, Vec3::NEG_Z);
        // Shared diagonal edge is hit.
        assert!(mesh
            .raycast(Vec3::new(0.0, 0.0, 1.0), Vec3::NEG_Z, 10.0)
            .is_some());
        // Misses: beside it, too short, parallel, zero direction.
        assert!(mesh
            .raycast(Vec3::new(1.5, 0.0, 1.0), Vec3::NEG_Z, 10.0)
            .is_none());
        assert!(mesh
            .raycast(Vec3::new(0.0, 0.0, 1.0), Vec3::NEG_Z, 0.5)
            .is_none());
        assert!(mesh
            .raycast(Vec3::new(0.0, 0.0, 1.0), Vec3::X, 10.0)
            .is_none());
        assert!(mesh
            .raycast(Vec3::new(0.0, 0.0, 1.0), Vec3::ZERO, 10.0)
            .is_none());
    }

    #[test]
    fn occlusion_ignores_the_end_surfaces() {
        let mesh = unit_square_at_z0();
        assert!(mesh.occluded(Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.0, 0.0, -1.0)));
        // Endpoint on the surface itself: not occluded by it.
        assert!(!mesh.occluded(Vec3::new(0.3, 0.3, 0.0), Vec3::new(0.0, 0.0, 2.0)));
        assert!(!mesh.occluded(Vec3::new(0.0, 0.0, 2.0), Vec3::new(0.3, 0.3, 0.0)));
        assert!(!mesh.occluded(Vec3::ONE, Vec3::ONE));
        // Far from the origin the float spacing grows; still no self-hit.
        let mut far = unit_square_at_z0();
        for v in &mut far.vertices {
            v.position[0] += 1e5;
        }
        assert!(!far.occluded(Vec3::new(1e5 + 0.3, 0.3, 0.0), Vec3::new(1e5, 0.0, 2.0)));
    }
}
