//! Decimation of a loaded single-material model to a target triangle count with
//! meshoptimizer's quadric edge-collapse simplifier (the `meshopt` crate). The thesis's dragon
//! has 6,514 faces and no such file is public; the table decimates the 100,000-face Stanford
//! dragon instead and says so.

use crate::error::{Error, Result};
use crate::scene::{area_weighted_normals, degeneracy, Mesh, MeshBuilder, Vertex};
use glam::Vec3;
use meshopt::SimplifyOptions;

/// The decimated mesh and what the simplifier did.
#[derive(Clone, Debug)]
pub struct Decimation {
    pub mesh: Mesh,
    pub from_triangles: usize,
    pub to_triangles: usize,
    /// meshoptimizer's resulting error, relative to the mesh extents.
    pub relative_error: f32,
}

/// Decimate `mesh` (one material) to at most `target_triangles` triangles. Vertices are
/// welded by position first (so UV or normal seams do not block collapses), normals are
/// recomputed area-weighted on the result, and unreferenced vertices are dropped. A mesh that
/// already has at most `target_triangles` triangles comes back unchanged.
pub fn decimate(mesh: &Mesh, target_triangles: usize) -> Result<Decimation> {
    let from = mesh.triangle_count();
    if mesh.ranges.len() != 1 {
        return Err(Error::Config(format!(
            "decimation needs a single-material mesh, this one has {} materials in use",
            mesh.ranges.len()
        )));
    }
    if target_triangles == 0 {
        return Err(Error::Config("cannot decimate to 0 triangles".into()));
    }
    if from <= target_triangles {
        return Ok(Decimation {
            mesh: mesh.clone(),
            from_triangles: from,
            to_triangles: from,
            relative_error: 0.0,
        });
    }
    let positions: Vec<[f32; 3]> = mesh.vertices.iter().map(|v| v.position).collect();
    let (unique, remap) = meshopt::generate_vertex_remap(&positions, Some(&mesh.indices));
    let indices = meshopt::remap_index_buffer(Some(&mesh.indices), positions.len(), &remap);
    let positions = meshopt::remap_vertex_buffer(&positions, unique, &remap);
    let mut relative_error = 0.0f32;
    // Target error 1 (the whole mesh extent): the triangle count is the only limit.
    let simplified = meshopt::simplify_decoder(
        &indices,
        &positions,
        target_triangles * 3,
        1.0,
        SimplifyOptions::None,
        Some(&mut relative_error),
    );
    let mesh = rebuild(mesh, &positions, &simplified);
    if mesh.indices.is_empty() {
        return Err(Error::Config(format!(
            "decimating {from} triangles to {target_triangles} left no triangle"
        )));
    }
    Ok(Decimation {
        to_triangles: mesh.triangle_count(),
        mesh,
        from_triangles: from,
        relative_error,
    })
}

/// A compact mesh of the triangles `indices` over `positions`, with the original material,
/// area-weighted normals and zero-area triangles removed.
fn rebuild(original: &Mesh, positions: &[[f32; 3]], indices: &[u32]) -> Mesh {
    let mut used: Vec<Option<u32>> = vec![None; positions.len()];
    let mut compact: Vec<Vec3> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::with_capacity(indices.len() / 3);
    for tri in indices.chunks_exact(3) {
        let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| Vec3::from(positions[i as usize]));
        if degeneracy(a, b, c).is_some() {
            continue;
        }
        let t = [tri[0], tri[1], tri[2]].map(|i| {
            *used[i as usize].get_or_insert_with(|| {
                compact.push(Vec3::from(positions[i as usize]));
                (compact.len() - 1) as u32
            })
        });
        triangles.push(t);
    }
    let normals = area_weighted_normals(&compact, &triangles);
    let mut b = MeshBuilder::new();
    let material = b.add_material(original.materials[original.ranges[0].material].clone());
    for (p, n) in compact.iter().zip(&normals) {
        b.push_vertex(Vertex::new(*p, *n, [0.0, 0.0]));
    }
    for t in &triangles {
        b.push_triangle(material, *t);
    }
    let stats = b.stats_mut();
    stats.faces = triangles.len();
    stats.triangles = triangles.len();
    stats.warnings = original.stats.warnings.clone();
    b.build()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Material;
    use std::f32::consts::{PI, TAU};

    /// A unit UV sphere. Every ring repeats its first vertex at the seam (as a UV-mapped
    /// export would), so welding is needed for a closed surface.
    fn sphere(rings: u32, segments: u32) -> Mesh {
        let mut b = MeshBuilder::new();
        let m = b.add_material(Material::colour("grey", [0.5; 3]));
        for r in 0..=rings {
            let theta = PI * r as f32 / rings as f32;
            for s in 0..=segments {
                let phi = TAU * s as f32 / segments as f32;
                let p = Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                );
                b.push_vertex(Vertex::new(p, p, [0.0, 0.0]));
            }
        }
        let at = |r: u32, s: u32| r * (segments + 1) + s;
        for r in 0..rings {
            for s in 0..segments {
                let (a, bb, c, d) = (at(r, s), at(r, s + 1), at(r + 1, s), at(r + 1, s + 1));
                if r > 0 {
                    b.push_triangle(m, [a, bb, c]);
                }
                if r + 1 < rings {
                    b.push_triangle(m, [bb, d, c]);
                }
            }
        }
        b.build()
    }

    #[test]
    fn sphere_reaches_target_and_keeps_its_shape() {
        let mesh = sphere(40, 60);
        let from = mesh.triangle_count();
        let d = decimate(&mesh, 500).unwrap();
        assert_eq!(d.from_triangles, from);
        assert!(
            (400..=500).contains(&d.to_triangles),
            "{} triangles",
            d.to_triangles
        );
        assert_eq!(d.mesh.triangle_count(), d.to_triangles);
        assert_eq!(d.mesh.ranges.len(), 1);
        assert!(d
            .mesh
            .indices
            .iter()
            .all(|&i| (i as usize) < d.mesh.vertices.len()));
        // Every vertex is referenced, still near the unit sphere, with an outward unit normal.
        let mut referenced = vec![false; d.mesh.vertices.len()];
        for &i in &d.mesh.indices {
            referenced[i as usize] = true;
        }
        assert!(referenced.iter().all(|&r| r));
        // (A coarse fan's area-weighted normal may lean, never turn inwards.)
        let mut alignment = 0.0;
        for v in &d.mesh.vertices {
            let p = v.pos();
            let n = Vec3::from(v.normal);
            assert!((p.length() - 1.0).abs() < 0.05, "{p}");
            assert!((n.length() - 1.0).abs() < 1e-4);
            assert!(n.dot(p.normalize()) > 0.5, "normal {n} at {p}");
            alignment += n.dot(p.normalize()) / d.mesh.vertices.len() as f32;
        }
        assert!(alignment > 0.98, "mean cosine {alignment}");
        assert!(d.relative_error > 0.0 && d.relative_error < 0.05);
        let e = d.mesh.bounds.extent();
        assert!(e.abs_diff_eq(Vec3::splat(2.0), 0.1), "{e}");
    }

    #[test]
    fn small_meshes_are_unchanged() {
        let mesh = sphere(4, 6);
        let d = decimate(&mesh, 10_000).unwrap();
        assert_eq!(d.mesh, mesh);
        assert_eq!(d.to_triangles, mesh.triangle_count());
    }

    #[test]
    fn several_materials_or_zero_target_are_errors() {
        let mut b = MeshBuilder::new();
        let red = b.add_material(Material::colour("red", [1.0, 0.0, 0.0]));
        let blue = b.add_material(Material::colour("blue", [0.0, 0.0, 1.0]));
        let tri = [Vec3::ZERO, Vec3::X, Vec3::Y];
        b.add_flat_polygon(red, &tri, Vec3::Z);
        b.add_flat_polygon(blue, &tri, Vec3::Z);
        let e = decimate(&b.build(), 1).unwrap_err().to_string();
        assert!(e.contains("single-material"), "{e}");
        assert!(decimate(&sphere(4, 6), 0).is_err());
    }
}
