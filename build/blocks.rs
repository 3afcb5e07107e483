//! naga reflection of the shared blocks a module declares (see `block_layout.rs`).

use super::block_layout::{Block, Member, GENERATED};

fn member_type(
    module: &naga::Module,
    ty: naga::Handle<naga::Type>,
) -> Option<(&'static str, &'static str)> {
    use naga::{ScalarKind as K, TypeInner as T, VectorSize as V};
    Some(match &module.types[ty].inner {
        // Atomically updated members are plain 32-bit integers to the host.
        T::Scalar(s) | T::Atomic(s) if s.width == 4 => match s.kind {
            K::Float => ("float", "f32"),
            K::Uint => ("uint", "u32"),
            K::Sint => ("int", "i32"),
            _ => return None,
        },
        T::Vector { size, scalar } if scalar.width == 4 => match (scalar.kind, size) {
            (K::Float, V::Bi) => ("vec2", "[f32; 2]"),
            (K::Float, V::Tri) => ("vec3", "[f32; 3]"),
            (K::Float, V::Quad) => ("vec4", "[f32; 4]"),
            (K::Uint, V::Bi) => ("uvec2", "[u32; 2]"),
            (K::Uint, V::Tri) => ("uvec3", "[u32; 3]"),
            (K::Uint, V::Quad) => ("uvec4", "[u32; 4]"),
            (K::Sint, V::Bi) => ("ivec2", "[i32; 2]"),
            (K::Sint, V::Tri) => ("ivec3", "[i32; 3]"),
            (K::Sint, V::Quad) => ("ivec4", "[i32; 4]"),
            _ => return None,
        },
        // Column-major with 16-byte columns: the same bytes in std140 and std430.
        T::Matrix {
            columns: V::Quad,
            rows: V::Quad,
            scalar,
        } if scalar.width == 4 => ("mat4", "[f32; 16]"),
        _ => return None,
    })
}

/// A pass that fills several effects' counters declares one copy of the block per lane
/// (`Counters0`, `Counters1`, ...): each is checked as `Counters`.
fn lane_copy_of(name: &str) -> &str {
    match name.strip_prefix("Counters") {
        Some(k) if !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit()) => "Counters",
        _ => name,
    }
}

/// The generated blocks a module declares, by GLSL name.
pub fn reflect_blocks(module: &naga::Module, file: &str) -> Result<Vec<Block>, String> {
    let mut out = Vec::new();
    for (_, var) in module.global_variables.iter() {
        let ty = &module.types[var.ty];
        let Some(name) = ty.name.as_deref().map(lane_copy_of) else {
            continue;
        };
        if !GENERATED.iter().any(|(g, _)| *g == name) {
            continue;
        }
        let naga::TypeInner::Struct { members, span } = &ty.inner else {
            continue;
        };
        let mut block = Block {
            name: name.to_string(),
            size: *span,
            members: Vec::new(),
        };
        for (i, m) in members.iter().enumerate() {
            let mname = m.name.clone().unwrap_or_default();
            if let naga::TypeInner::Array {
                size: naga::ArraySize::Dynamic,
                ..
            } = module.types[m.ty].inner
            {
                if i + 1 != members.len() {
                    return Err(format!(
                        "{file}: block {name}: runtime array {mname} is not last"
                    ));
                }
                block.size = m.offset;
                continue;
            }
            let (glsl, rust) = member_type(module, m.ty).ok_or_else(|| {
                format!(
                    "{file}: block {name} member {mname}: type not supported by the Rust \
                     generator (use 32-bit scalars, vectors or mat4)"
                )
            })?;
            if mname.is_empty() {
                return Err(format!("{file}: block {name} member {i} has no name"));
            }
            block.members.push(Member {
                name: mname,
                offset: m.offset,
                glsl,
                rust,
            });
        }
        out.push(block);
    }
    Ok(out)
}
