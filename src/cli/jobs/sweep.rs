//! `ssgi sweep`: combinations of configuration keys, time against error.

use super::common::{context_options, finish, load};
use crate::bench::measure::last_camera;
use crate::bench::warmup::{before_path, Warmup};
use crate::cli::args::{Cli, SweepArgs};
use crate::config::RenderConfig;
use crate::error::Result;
use crate::reference::run::Session;
use crate::reference::store::default_dir;
use crate::reference::trace::{DEFAULT_AO_SAMPLES, DEFAULT_INDIRECT_SAMPLES};
use crate::reference::{RefBuffer, Settings};
use crate::sweep::keys::{combinations, help_table, parse_vary};
use crate::sweep::report::{maps_readme_text, write, SweepHeader};
use crate::sweep::{run, SweepSpec};
use crate::vk::Context;

pub fn sweep(cli: &Cli, args: &SweepArgs) -> Result<()> {
    if args.list_keys {
        print!("{}", help_table());
        return Ok(());
    }
    let varies = args
        .vary
        .iter()
        .map(|v| parse_vary(v))
        .collect::<Result<Vec<_>>>()?;
    let base = args.scene.render_config();
    let combos = combinations(&base, &varies)?;
    crate::files::prepare_dir(&args.out, "--out")?;
    let (scene, path) = load(cli, &args.scene)?;
    let longest_cycle = combos
        .iter()
        .map(|(_, c)| c.temporal.rotation_limit)
        .max()
        .unwrap_or(36);
    let (warmup, warmup_along_path) = before_path(
        args.warmup.unwrap_or(Warmup::Frames(longest_cycle + 4)),
        longest_cycle,
    );
    // The ground truth of the last frame, with the combinations' AO definition (one ground
    // truth serves every combination, so its radius and attenuation cannot vary; a single
    // value of either sets it for the whole sweep).
    let camera = last_camera(&scene, &path, args.frames, args.scene.fps);
    let defining = combos.first().map_or(base, |(_, c)| *c);
    let definition = |c: &RenderConfig| (c.ao.radius, c.ao.attenuation);
    if combos
        .iter()
        .any(|(_, c)| definition(c) != definition(&defining))
    {
        return Err(crate::error::Error::Config(
            "ao.radius and ao.attenuation define the ground truth's AO: give each one value per \
             sweep (sweep several in separate runs)"
                .into(),
        ));
    }
    let settings = Settings::for_render(&defining, &scene);
    let cache = (!args.no_cache).then(|| args.cache_dir.clone().unwrap_or_else(default_dir));
    if let Some(dir) = &cache {
        crate::files::prepare_dir(dir, "--cache-dir")?;
    }
    let (w, h) = args.scene.size;
    // Moving objects and light where the last frame has them.
    let posed = scene.posed(crate::scene::path::frame_time(
        args.frames.max(1) - 1,
        args.scene.fps,
    ));
    let mut truth = Session::start(&posed, camera, w, h, settings, cache, true)?;
    truth.ensure(RefBuffer::Ao, DEFAULT_AO_SAMPLES)?;
    truth.ensure(RefBuffer::Direct, 1)?;
    truth.ensure(RefBuffer::Indirect, DEFAULT_INDIRECT_SAMPLES)?;
    truth.save()?;
    let ctx = Context::new(&context_options(cli))?;
    eprintln!(
        "sweep: {} combination(s) x {} frames (+{warmup} warmup) on {}",
        combos.len(),
        args.frames,
        ctx.info.name
    );
    let spec = SweepSpec {
        scene: &scene,
        path: &path,
        frames: args.frames,
        warmup,
        warmup_along_path,
        fps: args.scene.fps,
        combinations: combos,
        progress: true,
    };
    let (rows, quality) = run(&ctx, &spec, &mut truth)?;
    truth.save()?;
    let header = SweepHeader {
        command: std::env::args().collect::<Vec<_>>().join(" "),
        scene: scene.name.clone(),
        path: path.name(),
        size: [w, h],
        frames: args.frames,
        warmup,
        warmup_along_path,
        fps: args.scene.fps,
        device: ctx.info.name.clone(),
        driver: ctx.info.driver.clone(),
        reference_rays_per_second: truth.reference.rays_per_second(),
    };
    let mut files = write(&args.out, &header, &rows, &quality)?;
    // Error maps of every combination's last frame against the ground truth.
    for (i, row) in rows.iter().enumerate() {
        if let Some(last) = &row.last {
            files.extend(crate::bench::ground_truth::write_error_maps(
                last,
                &truth.reference,
                &scene,
                crate::effects::estimated_terms(&row.config),
                &args.out.join("maps"),
                &format!("{i:02}"),
            )?);
            if let Some(conv) = &row.converged_last {
                files.extend(crate::bench::ground_truth::write_converged_maps(
                    last,
                    conv,
                    &args.out.join("maps"),
                    &format!("{i:02}"),
                )?);
            }
        }
    }
    if rows.iter().any(|r| r.last.is_some()) {
        let readme = args.out.join("maps").join("README.md");
        crate::bench::output::write_text(&readme, &maps_readme_text(&header, &rows))?;
        files.push(readme);
    }
    eprintln!("wrote {} files to {}", files.len(), args.out.display());
    finish(&ctx)
}
