//! Compiles every `shaders/*.{vert,frag,comp}` and `shaders/<effect>/*.{vert,frag,comp}` (an
//! effect's passes, beside its private headers) and each of their permutations to SPIR-V with
//! glslang, validates the result with naga and generates `shaders.rs` in OUT_DIR: one
//! `ShaderModuleInfo` per module holding its SPIR-V and its reflected bindings, push-constant
//! size and workgroup size, so the Rust side cannot silently disagree with the shaders.
//!
//! `shaders/probes/*.comp` are test probes, not passes: compiled and reflected the same way but
//! listed in `PROBES` instead of `ALL`: no frame pass uses them; tests and diagnostics (the
//! renderer's numerical audit) create pipelines from them.
//!
//! Permutations: a line `// @permutation <suffix>: NAME=VALUE NAME2` in a shader compiles an
//! extra module `<STEM>_<EXT>_<SUFFIX>` with those `#define`s (a value `{HISTORY_FORMATS}`: one
//! module per history format in use, see `permutations`). Without such lines one module is
//! compiled with no defines.
//!
//! Storage images: naga's format of each is kept (`storage_formats`), so the passes can check
//! it against the image they bind (`passes::decl`).

#[path = "build/block_layout.rs"]
mod block_layout;
#[path = "build/blocks.rs"]
mod blocks;

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Resolves `#include "x.glsl"` in the including shader's own folder first (an effect's
/// private headers live beside its passes), then in `shaders/include/`.
struct Includer {
    dirs: Vec<PathBuf>,
}

impl glslang::include::IncludeHandler for Includer {
    fn include(
        &mut self,
        _ty: glslang::include::IncludeType,
        header_name: &str,
        _includer_name: &str,
        _depth: usize,
    ) -> Option<glslang::include::IncludeResult> {
        let data = self
            .dirs
            .iter()
            .find_map(|d| std::fs::read_to_string(d.join(header_name)).ok())?;
        Some(glslang::include::IncludeResult {
            name: header_name.to_string(),
            data,
        })
    }
}

struct Permutation {
    suffix: String,
    defines: Vec<(String, Option<String>)>,
}

/// A permutation line's value `{HISTORY_FORMATS}` stands for each history format the shared
/// constants declare (their `*_HISTORY_FORMAT` values, each once): the line becomes one
/// permutation per combination, its suffix extended by the values chosen (`2_rgba32f_rgba16f`).
/// So a pass that writes several effects' histories (reproject.comp's lanes) is compiled for
/// exactly the formats in use, and changing one effect's format stays one line.
const HISTORY_FORMATS: &str = "{HISTORY_FORMATS}";

fn permutations(source: &str, constants: &[(String, Constant)]) -> Vec<Permutation> {
    let mut history_formats: Vec<String> = Vec::new();
    for (name, value) in constants {
        if let (true, Constant::Format(glsl, _)) = (name.ends_with("_HISTORY_FORMAT"), value) {
            if !history_formats.iter().any(|f| f == glsl) {
                history_formats.push(glsl.to_string());
            }
        }
    }
    let mut out = Vec::new();
    for line in source.lines() {
        let Some(rest) = line.trim().strip_prefix("// @permutation ") else {
            continue;
        };
        let (suffix, defs) = rest.split_once(':').unwrap_or((rest, ""));
        let mut expanded = vec![Permutation {
            suffix: suffix.trim().to_string(),
            defines: Vec::new(),
        }];
        for d in defs.split_whitespace() {
            let (name, value) = match d.split_once('=') {
                Some((k, v)) => (k.to_string(), Some(v.to_string())),
                None => (d.to_string(), None),
            };
            if value.as_deref() != Some(HISTORY_FORMATS) {
                for p in &mut expanded {
                    p.defines.push((name.clone(), value.clone()));
                }
                continue;
            }
            let mut next = Vec::new();
            for p in &expanded {
                for f in &history_formats {
                    let mut defines = p.defines.clone();
                    defines.push((name.clone(), Some(f.clone())));
                    next.push(Permutation {
                        suffix: format!("{}_{f}", p.suffix),
                        defines,
                    });
                }
            }
            expanded = next;
        }
        out.extend(expanded);
    }
    if out.is_empty() {
        out.push(Permutation {
            suffix: String::new(),
            defines: Vec::new(),
        });
    }
    out
}

/// glslang reports `ERROR: 0:LINE: message`; rewrite to `file:LINE: message` so the build log
/// names the shader file.
fn locate_errors(file: &Path, log: &str) -> String {
    let name = file.display().to_string();
    log.lines()
        .map(|l| {
            let l = l
                .trim_start_matches("ERROR: ")
                .trim_start_matches("WARNING: ");
            match l.strip_prefix("0:") {
                Some(rest) => format!("{name}:{rest}"),
                None => l.to_string(),
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn compile(
    compiler: &glslang::Compiler,
    file: &Path,
    source: &str,
    stage: glslang::ShaderStage,
    perm: &Permutation,
    include_dir: &Path,
) -> Result<Vec<u32>, String> {
    let src = glslang::ShaderSource::from(source);
    let options = glslang::CompilerOptions {
        source_language: glslang::SourceLanguage::GLSL,
        target: glslang::Target::Vulkan {
            version: glslang::VulkanVersion::Vulkan1_3,
            spirv_version: glslang::SpirvVersion::SPIRV1_6,
        },
        version_profile: None,
        messages: glslang::ShaderMessage::DEFAULT,
    };
    // `file` is relative to the crate root, the folder above shaders/include/.
    let root = include_dir.ancestors().nth(2).unwrap_or(Path::new("."));
    let own_dir = root.join(file.parent().unwrap_or(Path::new("shaders")));
    let mut includer = Includer {
        dirs: vec![own_dir.to_path_buf(), include_dir.to_path_buf()],
    };
    let defines: Vec<(&str, Option<&str>)> = perm
        .defines
        .iter()
        .map(|(k, v)| (k.as_str(), v.as_deref()))
        .collect();
    let input = glslang::ShaderInput::new(
        &src,
        stage,
        &options,
        Some(defines.as_slice()),
        Some(&mut includer),
    )
    .map_err(|e| format!("{}: {e}", file.display()))?;
    let shader = compiler.create_shader(input).map_err(|e| {
        let log = match &e {
            glslang::error::GlslangError::ParseError(l)
            | glslang::error::GlslangError::PreprocessError(l)
            | glslang::error::GlslangError::LinkError(l) => l.log.clone(),
            other => other.to_string(),
        };
        locate_errors(file, &log)
    })?;
    let words = shader
        .compile()
        .map_err(|e| format!("{}: {e}", file.display()))?;
    Ok(words)
}

fn descriptor_kind(module: &naga::Module, var: &naga::GlobalVariable) -> Option<&'static str> {
    let mut ty = &module.types[var.ty].inner;
    if let naga::TypeInner::BindingArray { base, .. } = ty {
        ty = &module.types[*base].inner;
    }
    Some(match var.space {
        naga::AddressSpace::Uniform => "UniformBuffer",
        naga::AddressSpace::Storage { .. } => "StorageBuffer",
        naga::AddressSpace::Handle => match ty {
            naga::TypeInner::Sampler { .. } => "Sampler",
            naga::TypeInner::Image {
                class: naga::ImageClass::Storage { .. },
                ..
            } => "StorageImage",
            naga::TypeInner::Image { .. } => "SampledImage",
            _ => return None,
        },
        _ => return None,
    })
}

fn reflect(
    file: &Path,
    words: &[u32],
    ident: &str,
    suffix: &str,
    out: &mut String,
    shared_blocks: &mut BTreeMap<String, (block_layout::Block, String)>,
) -> Result<(), String> {
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
    let options = naga::front::spv::Options {
        adjust_coordinate_space: false,
        strict_capabilities: false,
        block_ctx_dump_prefix: None,
    };
    let module = naga::front::spv::parse_u8_slice(&bytes, &options)
        .map_err(|e| format!("{}: naga could not parse the SPIR-V: {e}", file.display()))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .map_err(|e| format!("{}: naga validation failed: {e:?}", file.display()))?;
    let entry = module
        .entry_points
        .first()
        .ok_or_else(|| format!("{}: no entry point", file.display()))?;
    let stage = match entry.stage {
        naga::ShaderStage::Vertex => "Vertex",
        naga::ShaderStage::Fragment => "Fragment",
        naga::ShaderStage::Compute => "Compute",
        other => return Err(format!("{}: unsupported stage {other:?}", file.display())),
    };
    let declared_blocks = blocks::reflect_blocks(&module, &file.display().to_string())?;
    block_layout::merge(
        shared_blocks,
        declared_blocks.clone(),
        &file.display().to_string(),
    )?;
    let mut layouter = naga::proc::Layouter::default();
    layouter
        .update(module.to_ctx())
        .map_err(|e| format!("{}: layout: {e}", file.display()))?;
    let mut bindings = Vec::new();
    let mut storage_formats = Vec::new();
    let mut push_constant_bytes = 0u32;
    for (_, var) in module.global_variables.iter() {
        if var.space == naga::AddressSpace::Immediate {
            push_constant_bytes = layouter[var.ty].size;
            continue;
        }
        let (Some(rb), Some(kind)) = (&var.binding, descriptor_kind(&module, var)) else {
            continue;
        };
        let count = match module.types[var.ty].inner {
            naga::TypeInner::BindingArray {
                size: naga::ArraySize::Constant(n),
                ..
            } => n.get(),
            _ => 1,
        };
        bindings.push((rb.group, rb.binding, kind, count));
        if let naga::TypeInner::Image {
            class: naga::ImageClass::Storage { format, .. },
            ..
        } = module.types[var.ty].inner
        {
            let vk = vk_storage_format(format).ok_or_else(|| {
                format!(
                    "{}: binding {}: storage format {format:?} has no Vulkan format in \
                     build.rs's vk_storage_format",
                    file.display(),
                    rb.binding
                )
            })?;
            storage_formats.push((rb.group, rb.binding, vk));
        }
    }
    bindings.sort();
    storage_formats.sort();
    let file_name = file.file_name().unwrap().to_string_lossy();
    // The module's name: its path under shaders/ (`ao/ssao_full.comp` for an effect's pass).
    let source_name = file
        .strip_prefix("shaders")
        .unwrap_or(file)
        .to_string_lossy()
        .replace('\\', "/");
    let spv_name = if suffix.is_empty() {
        format!("{file_name}.spv")
    } else {
        format!("{file_name}.{suffix}.spv")
    };
    let wg = entry.workgroup_size;
    let _ = writeln!(
        out,
        "pub static {ident}: ShaderModuleInfo = ShaderModuleInfo {{\n    name: \"{source_name}\",\n    permutation: \"{suffix}\",\n    stage: ShaderStage::{stage},\n    spirv: include_bytes!(concat!(env!(\"OUT_DIR\"), \"/shaders/{spv_name}\")),\n    bindings: &["
    );
    for (set, binding, kind, count) in bindings {
        let _ = writeln!(
            out,
            "        ReflectedBinding {{ set: {set}, binding: {binding}, kind: DescriptorKind::{kind}, count: {count} }},"
        );
    }
    let _ = writeln!(out, "    ],\n    storage_formats: &[");
    for (set, binding, format) in storage_formats {
        let _ = writeln!(
            out,
            "        StorageImageFormat {{ set: {set}, binding: {binding}, format: ash::vk::Format::{format} }},"
        );
    }
    let _ = writeln!(
        out,
        "    ],\n    push_constant_bytes: {push_constant_bytes},\n    workgroup_size: [{}, {}, {}],\n    blocks: {},\n}};\n",
        wg[0],
        wg[1],
        wg[2],
        block_layout::module_blocks(&declared_blocks)
    );
    let out_dir = PathBuf::from(std::env::var("OUT_DIR").unwrap()).join("shaders");
    std::fs::write(out_dir.join(spv_name), &bytes).map_err(|e| e.to_string())?;
    Ok(())
}

/// `pub const NAME: u32 = VALUE;` for every `#define NAME VALUE[u]` line of the shared
/// constants header (shaders/include/shared_constants.glsl): the constants both sides use,
/// defined once. Any other `#define` there (but its include guard) fails the build.
/// A shared constant's value.
enum Constant {
    Uint(u32),
    /// A storage image format: its GLSL layout qualifier and the Vulkan format's name.
    Format(String, &'static str),
}

/// The Vulkan format of a GLSL storage-image layout qualifier (those ssgi uses).
fn vk_format_of_glsl(glsl: &str) -> Option<&'static str> {
    Some(match glsl {
        "rgba32f" => "R32G32B32A32_SFLOAT",
        "rgba16f" => "R16G16B16A16_SFLOAT",
        "rg32f" => "R32G32_SFLOAT",
        "rg16f" => "R16G16_SFLOAT",
        "r32f" => "R32_SFLOAT",
        "r16f" => "R16_SFLOAT",
        "rgba8" => "R8G8B8A8_UNORM",
        "r32ui" => "R32_UINT",
        "rgba32ui" => "R32G32B32A32_UINT",
        "r11f_g11f_b10f" => "B10G11R11_UFLOAT_PACK32",
        _ => return None,
    })
}

/// The Vulkan format naga reflected for a storage image (the same set as `vk_format_of_glsl`).
fn vk_storage_format(f: naga::StorageFormat) -> Option<&'static str> {
    use naga::StorageFormat as S;
    vk_format_of_glsl(match f {
        S::Rgba32Float => "rgba32f",
        S::Rgba16Float => "rgba16f",
        S::Rg32Float => "rg32f",
        S::Rg16Float => "rg16f",
        S::R32Float => "r32f",
        S::R16Float => "r16f",
        S::Rgba8Unorm => "rgba8",
        S::R32Uint => "r32ui",
        S::Rgba32Uint => "rgba32ui",
        S::Rg11b10Ufloat => "r11f_g11f_b10f",
        _ => return None,
    })
}

/// The `#define NAME VALUE` lines of shaders/include/shared_constants.glsl: an unsigned
/// integer (`64u`) or a storage image format (`rgba32f`); anything else fails the build.
fn read_shared_constants(header: &Path) -> Vec<(String, Constant)> {
    let text =
        std::fs::read_to_string(header).unwrap_or_else(|e| panic!("{}: {e}", header.display()));
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let Some(rest) = line.trim().strip_prefix("#define ") else {
            continue;
        };
        let mut words = rest.split_whitespace();
        let name = words.next().unwrap_or_default();
        if name == "SHARED_CONSTANTS_GLSL" {
            continue;
        }
        let word = words.next().unwrap_or_default();
        let value = match (word.strip_suffix('u'), vk_format_of_glsl(word)) {
            (Some(v), _) if v.parse::<u32>().is_ok() => Constant::Uint(v.parse().unwrap()),
            (_, Some(vk)) => Constant::Format(word.to_string(), vk),
            _ => panic!(
                "{}:{}: a shared constant is `#define NAME VALUEu` (an unsigned integer) or \
                 `#define NAME FORMAT` (a storage format build.rs's vk_format_of_glsl knows)",
                header.display(),
                n + 1
            ),
        };
        out.push((name.to_string(), value));
    }
    out
}

/// The Rust side of the shared constants: `pub const NAME: u32` or `: ash::vk::Format`.
fn shared_constants(constants: &[(String, Constant)]) -> String {
    let mut out =
        String::from("// The shared constants (shaders/include/shared_constants.glsl).\n");
    for (name, value) in constants {
        let _ = match value {
            Constant::Uint(v) => writeln!(out, "pub const {name}: u32 = {v};"),
            Constant::Format(glsl, vk) => writeln!(
                out,
                "/// `{glsl}` in the shaders.\npub const {name}: ash::vk::Format = ash::vk::Format::{vk};"
            ),
        };
    }
    out
}

fn main() {
    let root = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap());
    let shader_dir = root.join("shaders");
    let include_dir = shader_dir.join("include");
    let out_dir = PathBuf::from(std::env::var("OUT_DIR").unwrap());
    std::fs::create_dir_all(out_dir.join("shaders")).unwrap();
    println!("cargo:rerun-if-changed=shaders");
    println!("cargo:rerun-if-changed=shaders/include");

    let shader_files = |dir: &Path| -> Vec<PathBuf> {
        let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
            .map(|entries| entries.filter_map(|e| e.ok().map(|e| e.path())).collect())
            .unwrap_or_default();
        files.retain(|p| {
            matches!(
                p.extension().and_then(|e| e.to_str()),
                Some("vert" | "frag" | "comp")
            )
        });
        files.sort();
        files
    };
    let probe_dir = shader_dir.join("probes");
    println!("cargo:rerun-if-changed=shaders/probes");
    // Passes: shaders/ and each effect's folder under it (its passes and private headers).
    let mut pass_dirs = vec![shader_dir.clone()];
    let mut effect_dirs: Vec<PathBuf> = std::fs::read_dir(&shader_dir)
        .map(|entries| entries.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    effect_dirs.retain(|d| d.is_dir() && *d != include_dir && *d != probe_dir);
    effect_dirs.sort();
    for d in &effect_dirs {
        println!("cargo:rerun-if-changed={}", d.display());
        for e in std::fs::read_dir(d).into_iter().flatten().flatten() {
            println!("cargo:rerun-if-changed={}", e.path().display());
        }
    }
    pass_dirs.extend(effect_dirs);
    let files: Vec<(PathBuf, bool)> = pass_dirs
        .iter()
        .flat_map(|d| shader_files(d))
        .map(|f| (f, false))
        .chain(shader_files(&probe_dir).into_iter().map(|f| (f, true)))
        .collect();
    assert!(
        files.iter().any(|(_, probe)| !probe),
        "no shaders in shaders/"
    );
    if let Ok(entries) = std::fs::read_dir(&include_dir) {
        for e in entries.flatten() {
            println!("cargo:rerun-if-changed={}", e.path().display());
        }
    }

    let constants = read_shared_constants(&include_dir.join("shared_constants.glsl"));
    let compiler = glslang::Compiler::acquire().expect("glslang compiler");
    let mut generated = String::from("// Generated by build.rs from shaders/: do not edit.\n\n");
    let mut all = Vec::new();
    let mut probes = Vec::new();
    let mut errors = Vec::new();
    let mut shared_blocks = BTreeMap::new();
    for (file, probe) in &files {
        println!("cargo:rerun-if-changed={}", file.display());
        let rel = file.strip_prefix(&root).unwrap_or(file).to_path_buf();
        let source = std::fs::read_to_string(file).expect("read shader");
        let ext = file.extension().unwrap().to_str().unwrap();
        let stage = match ext {
            "vert" => glslang::ShaderStage::Vertex,
            "frag" => glslang::ShaderStage::Fragment,
            _ => glslang::ShaderStage::Compute,
        };
        let stem = file.file_stem().unwrap().to_str().unwrap();
        for perm in permutations(&source, &constants) {
            let mut ident = format!("{}_{}", stem, ext).to_uppercase().replace('-', "_");
            if !perm.suffix.is_empty() {
                ident = format!("{ident}_{}", perm.suffix.to_uppercase());
            }
            match compile(compiler, &rel, &source, stage, &perm, &include_dir).and_then(|words| {
                reflect(
                    &rel,
                    &words,
                    &ident,
                    &perm.suffix,
                    &mut generated,
                    &mut shared_blocks,
                )
            }) {
                Ok(()) if all.contains(&ident) || probes.contains(&ident) => errors.push(format!(
                    "{}: module {ident} is also another folder's: a shader's name is its \
                     module's, so it must be unique across shaders/",
                    rel.display()
                )),
                Ok(()) if *probe => probes.push(ident),
                Ok(()) => all.push(ident),
                Err(e) => errors.push(e),
            }
        }
    }
    if !errors.is_empty() {
        for e in &errors {
            eprintln!("{e}");
        }
        panic!("shader compilation failed:\n{}", errors.join("\n"));
    }
    let _ = writeln!(generated, "pub static ALL: &[&ShaderModuleInfo] = &[");
    for ident in &all {
        let _ = writeln!(generated, "    &{ident},");
    }
    let _ = writeln!(generated, "];\n");
    let _ = writeln!(generated, "pub static PROBES: &[&ShaderModuleInfo] = &[");
    for ident in &probes {
        let _ = writeln!(generated, "    &{ident},");
    }
    let _ = writeln!(generated, "];\n");
    generated.push_str(&block_layout::generate(&shared_blocks));
    generated.push_str(&shared_constants(&constants));
    std::fs::write(out_dir.join("shaders.rs"), generated).unwrap();
}
