//! The scene's triangles and a BVH over them in the layout the GPU traverses
//! (shaders/include/bvh.glsl, issue 64): obvhs's BVH2 (binary; its compressed wide CWBVH, which
//! the CPU reference walks, wants a traversal of its own) as 32-byte nodes, and the triangles
//! in leaf order, so a leaf indexes them directly with no second lookup.

use super::accel::obvhs_triangles;
use super::mesh::Mesh;
use obvhs::bvh2::builder::build_bvh2_from_tris;
use obvhs::BvhBuildParams;

/// Deepest tree the shaders' traversal stack holds (bvh.glsl's BVH_STACK): a node at depth d
/// leaves at most d + 1 entries on the stack.
pub const BVH_MAX_DEPTH: usize = 61;

/// Bytes of a node (bvh.glsl's `BvhNode`, std430) and of a triangle (`BvhTriangle`).
pub const NODE_BYTES: usize = 32;
pub const TRIANGLE_BYTES: usize = 48;

/// The BVH and triangles as the GPU reads them.
pub struct FlatBvh {
    /// `NODE_BYTES` per node: box minimum (3 floats), triangle count (0: an inner node whose
    /// children are nodes `first` and `first + 1`), box maximum, `first`. Node 0 is the root.
    pub nodes: Vec<u8>,
    /// `TRIANGLE_BYTES` per triangle in leaf order: its corners as vec4s, the first's w holding
    /// the mesh's triangle index as bits.
    pub triangles: Vec<u8>,
    /// The tree's depth (a lone root is 0).
    pub depth: usize,
}

impl FlatBvh {
    /// Over every triangle of `mesh` (obvhs's "medium" build, as the CPU reference's). A mesh
    /// without triangles gets one empty root box, which every ray misses.
    pub fn new(mesh: &Mesh) -> Result<Self, String> {
        let tris = obvhs_triangles(mesh);
        if tris.is_empty() {
            let mut nodes = Vec::with_capacity(NODE_BYTES);
            push_node(&mut nodes, [f32::MAX; 3], 0, [-f32::MAX; 3], 0);
            return Ok(Self {
                nodes,
                triangles: Vec::new(),
                depth: 0,
            });
        }
        let mut build_time = std::time::Duration::ZERO;
        let bvh = build_bvh2_from_tris(&tris, BvhBuildParams::medium_build(), &mut build_time);
        let mut nodes = Vec::with_capacity(bvh.nodes.len() * NODE_BYTES);
        for n in &bvh.nodes {
            push_node(
                &mut nodes,
                n.aabb.min.into(),
                n.prim_count,
                n.aabb.max.into(),
                n.first_index,
            );
        }
        // Leaves index `primitive_indices`; the triangles go in that order instead.
        let mut triangles = Vec::with_capacity(bvh.primitive_indices.len() * TRIANGLE_BYTES);
        for &id in &bvh.primitive_indices {
            let t = &tris[id as usize];
            for (corner, w) in [(t.v0, f32::from_bits(id)), (t.v1, 0.0), (t.v2, 0.0)] {
                for c in [corner.x, corner.y, corner.z, w] {
                    triangles.extend_from_slice(&c.to_le_bytes());
                }
            }
        }
        let depth = depth(&bvh.nodes);
        if depth > BVH_MAX_DEPTH {
            return Err(format!(
                "the scene's BVH is {depth} levels deep; the GPU traversal holds {BVH_MAX_DEPTH} \
                 (shaders/include/bvh.glsl's BVH_STACK)"
            ));
        }
        Ok(Self {
            nodes,
            triangles,
            depth,
        })
    }

    pub fn node_count(&self) -> usize {
        self.nodes.len() / NODE_BYTES
    }
}

fn push_node(out: &mut Vec<u8>, lo: [f32; 3], count: u32, hi: [f32; 3], first: u32) {
    for c in lo {
        out.extend_from_slice(&c.to_le_bytes());
    }
    out.extend_from_slice(&count.to_le_bytes());
    for c in hi {
        out.extend_from_slice(&c.to_le_bytes());
    }
    out.extend_from_slice(&first.to_le_bytes());
}

/// The depth of the tree under node 0 (iterative: a degenerate tree must not overflow the
/// CPU's stack either).
fn depth(nodes: &[obvhs::bvh2::node::Bvh2Node]) -> usize {
    let mut deepest = 0;
    let mut stack = vec![(0usize, 0usize)];
    while let Some((i, d)) = stack.pop() {
        deepest = deepest.max(d);
        let n = &nodes[i];
        if n.prim_count == 0 {
            let first = n.first_index as usize;
            stack.push((first, d + 1));
            stack.push((first + 1, d + 1));
        }
    }
    deepest
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nodes_and_triangles_have_the_shaders_sizes() {
        let box_mesh = crate::scene::cornell_box().mesh;
        let flat = FlatBvh::new(&box_mesh).unwrap();
        assert_eq!(flat.nodes.len() % NODE_BYTES, 0);
        assert_eq!(
            flat.triangles.len(),
            box_mesh.triangle_count() * TRIANGLE_BYTES
        );
        assert!(flat.node_count() >= 1 && flat.depth <= BVH_MAX_DEPTH);
        // Every mesh triangle appears once, by its index in the first corner's w.
        let mut seen: Vec<u32> = flat
            .triangles
            .chunks_exact(TRIANGLE_BYTES)
            .map(|t| u32::from_le_bytes(t[12..16].try_into().unwrap()))
            .collect();
        seen.sort_unstable();
        assert_eq!(
            seen,
            (0..box_mesh.triangle_count() as u32).collect::<Vec<_>>()
        );
    }
}

#[cfg(test)]
mod leaves {
    use super::*;

    fn f(b: &[u8], i: usize) -> f32 {
        f32::from_le_bytes(b[4 * i..4 * i + 4].try_into().unwrap())
    }
    fn u(b: &[u8], i: usize) -> u32 {
        u32::from_le_bytes(b[4 * i..4 * i + 4].try_into().unwrap())
    }

    /// Every leaf's box holds its triangles' corners, and every inner node's children exist:
    /// the flattening kept obvhs's tree and reordered the triangles to match.
    #[test]
    fn leaves_cover_their_triangles() {
        let mesh = crate::scene::cornell_box().mesh;
        let flat = FlatBvh::new(&mesh).unwrap();
        let n = flat.node_count();
        for i in 0..n {
            let b = &flat.nodes[i * 32..i * 32 + 32];
            let lo = [f(b, 0), f(b, 1), f(b, 2)];
            let count = u(b, 3);
            let hi = [f(b, 4), f(b, 5), f(b, 6)];
            let first = u(b, 7) as usize;
            if count == 0 {
                assert!(first + 1 < n, "node {i}: children {first} of {n}");
                continue;
            }
            for t in first..first + count as usize {
                let tb = &flat.triangles[t * 48..t * 48 + 48];
                for c in 0..3 {
                    for a in 0..3 {
                        let v = f(tb, 4 * c + a);
                        assert!(
                            v >= lo[a] - 1e-5 && v <= hi[a] + 1e-5,
                            "node {i} tri {t}: {v} outside {lo:?}..{hi:?}"
                        );
                    }
                }
            }
        }
    }
}
