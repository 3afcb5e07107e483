//! No two modules of the crate use each other: the arrows of docs/ARCHITECTURE.md point one
//! way. Reads `src/` and follows `crate::` / `super::` / `self::` paths (and a parent's use of
//! its child modules); unit-test modules at the end of a file are not counted.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Module path of a source file (`src/vk/mod.rs` -> `vk`, `src/lib.rs` -> ``).
fn module_of(rel: &Path) -> String {
    let mut parts: Vec<String> = rel
        .with_extension("")
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    if parts == ["lib"] || parts == ["main"] {
        parts.clear();
    }
    parts.join("::")
}

fn sources(dir: &Path, root: &Path, out: &mut BTreeMap<String, String>) {
    for entry in std::fs::read_dir(dir).unwrap().flatten() {
        let path = entry.path();
        if path.is_dir() {
            sources(&path, root, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let text = std::fs::read_to_string(&path).unwrap();
            let text = match text.find("#[cfg(test)]\nmod tests") {
                Some(i) => text[..i].to_string(),
                None => text,
            };
            out.insert(module_of(path.strip_prefix(root).unwrap()), text);
        }
    }
}

/// Every `crate::a::b`, `super::x`, `self::y` path in `text` (a path before `::{` too).
fn paths(text: &str) -> Vec<Vec<&str>> {
    let mut out = Vec::new();
    let bytes = text.as_bytes();
    for start in ["crate::", "super::", "self::"] {
        for (i, _) in text.match_indices(start) {
            if i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_') {
                continue;
            }
            let end = text[i..]
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == ':'))
                .map_or(text.len(), |n| i + n);
            let path: Vec<&str> = text[i..end].split("::").filter(|s| !s.is_empty()).collect();
            out.push(path);
        }
    }
    out
}

fn resolve(
    modules: &BTreeMap<String, String>,
    current: &str,
    is_dir: bool,
    path: &[&str],
) -> Option<String> {
    let mut base: Vec<&str> = if current.is_empty() {
        Vec::new()
    } else {
        current.split("::").collect()
    };
    let mut rest = path;
    match rest.first() {
        Some(&"crate") => base.clear(),
        Some(&"self") if !is_dir => {
            base.pop();
        }
        Some(&"self") => {}
        _ => {}
    }
    if rest.first() == Some(&"crate") || rest.first() == Some(&"self") {
        rest = &rest[1..];
    }
    while rest.first() == Some(&"super") {
        base.pop();
        rest = &rest[1..];
    }
    let full: Vec<&str> = base.iter().chain(rest).copied().collect();
    (0..=full.len())
        .rev()
        .map(|n| full[..n].join("::"))
        .find(|m| modules.contains_key(m))
}

fn src_root() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Every module of `src/` and its text (unit tests left out).
fn modules() -> BTreeMap<String, String> {
    let root = src_root();
    let mut modules = BTreeMap::new();
    sources(&root, &root, &mut modules);
    assert!(modules.len() > 50, "read only {} modules", modules.len());
    modules
}

/// Every module's uses of other modules (resolved paths and a parent's uses of its children).
fn module_uses() -> BTreeMap<String, BTreeSet<String>> {
    uses_of(&modules())
}

fn uses_of(modules: &BTreeMap<String, String>) -> BTreeMap<String, BTreeSet<String>> {
    let root = src_root();
    let mut uses: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (m, text) in modules {
        let dir_module = m.is_empty() || root.join(m.replace("::", "/")).is_dir();
        let mut deps = BTreeSet::new();
        for p in paths(text) {
            if let Some(d) = resolve(modules, m, dir_module, &p) {
                deps.insert(d);
            }
        }
        // A parent that uses items of its declared child modules.
        for line in text.lines() {
            let line = line.trim_start().trim_start_matches("pub ");
            if let Some(child) = line.strip_prefix("mod ").and_then(|l| l.strip_suffix(';')) {
                let used = text.contains(&format!("{child}::"));
                let child = if m.is_empty() {
                    child.to_string()
                } else {
                    format!("{m}::{child}")
                };
                if used {
                    deps.insert(child);
                }
            }
        }
        deps.remove(m);
        uses.insert(m.clone(), deps);
    }
    uses
}

#[test]
fn no_two_modules_use_each_other() {
    let uses = module_uses();
    let mut circles = Vec::new();
    for (a, deps) in &uses {
        for b in deps {
            if a < b && uses.get(b).is_some_and(|d| d.contains(a)) {
                circles.push(format!("{a} <-> {b}"));
            }
        }
    }
    assert!(
        circles.is_empty(),
        "modules that use each other:\n{}",
        circles.join("\n")
    );
}

#[test]
fn paths_resolve_to_modules() {
    let mut modules = BTreeMap::new();
    modules.insert("a".to_string(), String::new());
    modules.insert("a::b".to_string(), String::new());
    assert_eq!(
        resolve(&modules, "a::c", false, &["super", "b", "Thing"]),
        Some("a::b".into())
    );
    assert_eq!(
        resolve(&modules, "a::b", false, &["crate", "a", "X"]),
        Some("a".into())
    );
    assert_eq!(
        paths("use super::{x, y};\nlet v = crate::a::b::C;"),
        vec![vec!["crate", "a", "b", "C"], vec!["super"]]
    );
}

/// The layers of docs/ARCHITECTURE.md, lowest first: a module may use its own layer and the
/// ones below. `scene`, `reference`, `config` (with each effect's `config.rs`),
/// `shaders` (generated), `error`, `files` and `interrupt` are beside the stack: anyone may use them,
/// and they use only `vk` and each other.
fn layer(module: &str) -> usize {
    // An effect's or post stage's configuration (`effects::<effect>::config`: its parameters, their
    // validation and value parsers) is plain data in the effect's folder: `RenderConfig`
    // holds it, so it sits with `config` and may use only what `config` may.
    let parts: Vec<&str> = module.split("::").collect();
    if parts.len() == 3 && matches!(parts[0], "effects" | "post") && parts[2] == "config" {
        return 0;
    }
    match parts[0] {
        "error" | "files" | "interrupt" | "shaders" | "scene" | "reference" | "vk" | "config" => 0,
        "resources" => 1,
        "passes" => 2,
        "effects" | "post" => 3,
        "renderer" => 4,
        "frontend" | "plot" | "bench" | "stress" | "sweep" => 5,
        "cli" | "" => 6,
        other => panic!("module {other} has no layer: add it to tests/module_graph.rs"),
    }
}

/// Every use of a higher layer, as `user -> used`.
fn upward(uses: &BTreeMap<String, BTreeSet<String>>) -> Vec<String> {
    let mut upward: Vec<String> = Vec::new();
    for (a, deps) in uses {
        for b in deps {
            if layer(b) > layer(a) {
                upward.push(format!("{a} -> {b}"));
            }
        }
    }
    upward
}

#[test]
fn layers_are_used_downwards_only() {
    let upward = upward(&module_uses());
    assert!(
        upward.is_empty(),
        "uses up the layers (vk, scene, reference, config < resources < passes < effects, post < \
         renderer < frontend, plot, bench, sweep, stress < cli):\n{}",
        upward.join("\n")
    );
}

/// The check catches what it is for: imports planted in a copy of the tree, one up each step
/// of the stack, are each reported, and nothing else is.
#[test]
fn a_planted_upward_import_is_caught() {
    let plants = [
        ("vk::context", "crate::resources::targets::Targets"),
        ("passes::compute", "crate::effects::REGISTRY"),
        ("effects::ao", "crate::renderer::Renderer"),
        ("renderer::audit", "crate::bench::report::Report"),
        ("bench::report", "crate::cli::args::Cli"),
        ("config", "crate::sweep::keys"),
    ];
    for (module, import) in plants {
        let mut modules = modules();
        let text = modules
            .get_mut(module)
            .unwrap_or_else(|| panic!("no module {module}"));
        text.insert_str(0, &format!("use {import};\n"));
        let found = upward(&uses_of(&modules));
        assert_eq!(found.len(), 1, "{module} importing {import}: {found:?}");
        assert!(found[0].starts_with(&format!("{module} -> ")), "{found:?}");
    }
}
