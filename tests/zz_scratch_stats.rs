#[test]
fn stats() {
    let dir = std::path::Path::new("/work/shared/scenes");
    for name in ["bunny","sponza","venus","buddha","dragon","sibenik","conference","cornell-box/CornellBox-Original.obj"] {
        let t = std::time::Instant::now();
        let s = ssgi::scene::load_scene(name, Some(dir)).unwrap();
        let m = &s.mesh;
        println!("{name}: {:.3}s faces {} tris {} drawn {} dropped {} verts {} mats {} warn {:?} bounds {:?}", t.elapsed().as_secs_f64(), m.stats.faces, m.stats.triangles, m.triangle_count(), m.stats.dropped_degenerate, m.vertices.len(), m.materials.len(), m.stats.warnings, m.bounds);
    }
}
