//! Shared blocks (uniform blocks, push constants, storage-buffer headers) as the shaders declare
//! them, and the Rust structs generated from them, so the Rust side fills members by name and
//! cannot drift from the GLSL: a renamed, added or removed member is a compile error naming it,
//! and two shaders that declare the same block differently fail the build naming the member.
//! Pure (no naga) so that tests can include it.

use std::collections::BTreeMap;
use std::fmt::Write as _;

/// The blocks generated into Rust: GLSL block name -> Rust struct name.
pub const GENERATED: &[(&str, &str)] = &[
    ("Frame", "FrameBlock"),
    ("Ccipca", "CcipcaPush"),
    ("Svgf", "SvgfPush"),
    ("Ssdo", "SsdoParams"),
    ("Ao", "AoParams"),
    ("Sraa", "SraaPush"),
    ("Vpl", "VplParams"),
    ("Effect", "EffectPush"),
    ("Counters", "CountersHeader"),
    ("Material", "MaterialPush"),
    ("Probe", "ProbePush"),
    ("Reproject", "ReprojectPush"),
    ("ImageStats", "ImageStatsPush"),
    ("GBufferResolve", "GBufferResolvePush"),
    ("Overlay", "OverlayPush"),
];

#[derive(Clone, Debug, PartialEq)]
pub struct Member {
    pub name: String,
    pub offset: u32,
    /// GLSL spelling (`float`, `uvec2`, `mat4`).
    pub glsl: &'static str,
    /// Rust type of the generated field.
    pub rust: &'static str,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    pub name: String,
    /// Bytes up to the end of the last fixed-size member (a trailing runtime array is not part
    /// of the header).
    pub size: u32,
    pub members: Vec<Member>,
}

/// All declarations of each block must agree; returns the first module's, keyed by name.
pub fn merge(
    into: &mut BTreeMap<String, (Block, String)>,
    blocks: Vec<Block>,
    file: &str,
) -> Result<(), String> {
    for b in blocks {
        match into.get(&b.name) {
            None => {
                into.insert(b.name.clone(), (b, file.to_string()));
            }
            Some((first, first_file)) if *first != b => {
                return Err(describe_mismatch(first, first_file, &b, file));
            }
            Some(_) => {}
        }
    }
    Ok(())
}

fn describe_mismatch(a: &Block, a_file: &str, b: &Block, b_file: &str) -> String {
    let show = |m: Option<&Member>| match m {
        Some(m) => format!("{} {} at byte {}", m.glsl, m.name, m.offset),
        None => "nothing".to_string(),
    };
    let n = a.members.len().max(b.members.len());
    for i in 0..n {
        let (ma, mb) = (a.members.get(i), b.members.get(i));
        if ma != mb {
            return format!(
                "block {} differs between shaders: member {i} is {} in {a_file} but {} in {b_file}",
                a.name,
                show(ma),
                show(mb)
            );
        }
    }
    format!(
        "block {} differs between shaders: {} bytes in {a_file}, {} in {b_file}",
        a.name, a.size, b.size
    )
}

/// Rust source of the generated structs.
pub fn generate(blocks: &BTreeMap<String, (Block, String)>) -> String {
    let mut s = String::new();
    for (glsl_name, rust_name) in GENERATED {
        let Some((b, file)) = blocks.get(*glsl_name) else {
            continue;
        };
        let _ = writeln!(
            s,
            "/// The GLSL block `{glsl_name}` (first declared in `{file}`), member by member with \
             naga's offsets.\n#[derive(Clone, Copy, Debug, Default, PartialEq)]\npub struct {rust_name} {{"
        );
        for m in &b.members {
            let _ = writeln!(
                s,
                "    /// `{} {}` at byte {}.\n    pub {}: {},",
                m.glsl, m.name, m.offset, m.name, m.rust
            );
        }
        let _ = writeln!(s, "}}\n\nimpl {rust_name} {{");
        let _ = writeln!(s, "    /// Bytes of the block (the header, for a block ending in a runtime array).\n    pub const SIZE: usize = {};", b.size);
        let _ = writeln!(s, "    /// GLSL name of the block.\n    pub const GLSL_NAME: &'static str = \"{glsl_name}\";");
        let _ = writeln!(s, "    /// Every member: name, byte offset, GLSL type.\n    pub const MEMBERS: &'static [BlockMember] = &[");
        for m in &b.members {
            let _ = writeln!(
                s,
                "        BlockMember {{ name: \"{}\", offset: {}, glsl: \"{}\" }},",
                m.name, m.offset, m.glsl
            );
        }
        let _ = writeln!(s, "    ];");
        for m in &b.members {
            let _ = writeln!(
                s,
                "    pub const OFFSET_{}: usize = {};",
                m.name.to_uppercase(),
                m.offset
            );
        }
        let _ = writeln!(s, "\n    /// The block's bytes, every member at its reflected offset (padding zero).\n    pub fn to_bytes(&self) -> [u8; Self::SIZE] {{\n        let mut out = [0u8; Self::SIZE];");
        for m in &b.members {
            let _ = writeln!(
                s,
                "        BlockValue::put(&self.{}, &mut out, {});",
                m.name, m.offset
            );
        }
        let _ = writeln!(s, "        out\n    }}\n\n    /// The block read back from bytes laid out as in the shader.\n    pub fn from_bytes(bytes: &[u8; Self::SIZE]) -> Self {{\n        Self {{");
        for m in &b.members {
            let _ = writeln!(
                s,
                "            {}: BlockValue::get(bytes, {}),",
                m.name, m.offset
            );
        }
        let _ = writeln!(s, "        }}\n    }}\n}}\n");
    }
    s
}

/// Rust source for one module's list of reflected blocks.
pub fn module_blocks(blocks: &[Block]) -> String {
    let mut s = String::from("&[");
    for b in blocks {
        let _ = write!(
            s,
            "ReflectedBlock {{ name: \"{}\", size: {}, members: &[",
            b.name, b.size
        );
        for m in &b.members {
            let _ = write!(
                s,
                "BlockMember {{ name: \"{}\", offset: {}, glsl: \"{}\" }}, ",
                m.name, m.offset, m.glsl
            );
        }
        let _ = write!(s, "] }}, ");
    }
    s.push(']');
    s
}
