//! Vertex normals for meshes whose file has none (or unusable ones).

use glam::Vec3;

/// Area-weighted vertex normals: each vertex gets the sum of the unnormalised cross products
/// of its triangles (|cross| = 2 × area, so big faces weigh more), then normalised.
///
/// Guard: when the sum cancels out (e.g. a vertex shared by two back-to-back faces) it falls
/// back to the unit normal of the vertex's first non-degenerate triangle, and to +Y for a
/// vertex no usable triangle touches. `try_normalize` rejects zero and non-finite lengths,
/// so the test is scale-free.
pub fn area_weighted_normals(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<Vec3> {
    let mut sum = vec![Vec3::ZERO; positions.len()];
    let mut first: Vec<Option<Vec3>> = vec![None; positions.len()];
    for tri in triangles {
        let [a, b, c] = tri.map(|i| positions[i as usize]);
        let cross = (b - a).cross(c - a);
        let unit = cross.try_normalize();
        for &i in tri {
            sum[i as usize] += cross;
            if first[i as usize].is_none() {
                first[i as usize] = unit;
            }
        }
    }
    sum.into_iter()
        .zip(first)
        .map(|(s, f)| s.try_normalize().or(f).unwrap_or(Vec3::Y))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn larger_face_dominates() {
        // Vertex 0 is shared by a large +z triangle and a small +x triangle.
        let p = [
            Vec3::ZERO,
            Vec3::new(10.0, 0.0, 0.0),
            Vec3::new(0.0, 10.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        ];
        let n = area_weighted_normals(&p, &[[0, 1, 2], [0, 3, 4]]);
        let expected = Vec3::new(1.0, 0.0, 100.0).normalize();
        assert!(n[0].abs_diff_eq(expected, 1e-6), "{:?}", n[0]);
        assert!(n[1].abs_diff_eq(Vec3::Z, 1e-6));
    }

    #[test]
    fn cancelling_and_unused_vertices_fall_back() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::splat(5.0)];
        // The same triangle twice with opposite winding: the sum cancels.
        let n = area_weighted_normals(&p, &[[0, 1, 2], [0, 2, 1]]);
        assert!(n[0].abs_diff_eq(Vec3::Z, 1e-6));
        assert_eq!(n[3], Vec3::Y);
        assert!(n.iter().all(|v| v.is_normalized()));
    }
}
