//! `ssgi bench`: per-pass GPU times along a camera path, offscreen or presented, as a table
//! and JSON; `--compare-reuse` runs the path with reuse on and off and adds the speed-ups.

use super::common::{check_frames, context_options, finish, load};
use crate::bench::compare::Comparison;
use crate::bench::measure::{report_config, FlickerProbe, RunLength};
use crate::bench::warmup::{self, Outcome, Warmup};
use crate::bench::Report;
use crate::cli::args::{BenchArgs, Cli};
use crate::error::{Error, Result};
use crate::frontend::headless;
use crate::frontend::progress::Progress;
use crate::frontend::sink::FrameSink;
use crate::frontend::window_sink::open_sink;
use crate::renderer::Renderer;
use crate::scene::path::frame_time;
use crate::scene::{CameraPath, Scene};
use crate::vk::{Context, FrameTiming};
use std::sync::Arc;

fn write_json(path: &std::path::Path, value: &impl serde::Serialize) -> Result<()> {
    let text = serde_json::to_string_pretty(value)
        .map_err(|e| Error::Config(format!("JSON encoding failed: {e}")))?;
    crate::files::write_atomic(path, text.as_bytes())?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

/// Warm `renderer` up along `path` as `--warmup` asks, then measure `--frames` frames; the
/// report marks the warmup frames and leaves them out of the statistics.
fn measure(
    args: &BenchArgs,
    ctx: &Context,
    renderer: &mut Renderer,
    sink: &mut dyn FrameSink,
    path: &CameraPath,
) -> Result<Report> {
    let fps = args.scene.fps;
    let (mut timings, outcome) = warmup::run(renderer, sink, path, fps, args.warmup, true)?;
    let mut probe = FlickerProbe::default();
    timings.extend(headless::run_from(
        renderer,
        sink,
        path,
        outcome.frames..outcome.frames.saturating_add(args.frames),
        fps,
        true,
        &mut |r| {
            if args.flicker {
                probe.after_frame(r)?;
            }
            Ok(())
        },
    )?);
    eprintln!("{}", outcome.describe());
    let mut report = report(args, ctx, renderer, sink, path, &timings, outcome);
    if args.flicker {
        report.attach_flicker(&probe.measures);
        if let Some(f) = &report.flicker {
            eprintln!(
                "flicker (mean squared difference of consecutive frames): output {}, indirect \
                 light {}; {} of {} measured frames below {:.1e}",
                f.final_msd_mean.map_or("-".into(), |v| format!("{v:.3e}")),
                f.indirect_msd_mean
                    .map_or("-".into(), |v| format!("{v:.3e}")),
                f.frames_below,
                report.measured_frames,
                f.threshold
            );
        }
    }
    Ok(report)
}

/// The report of a run whose first `warmup.frames` frames were warmup.
fn report(
    args: &BenchArgs,
    ctx: &Context,
    renderer: &Renderer,
    sink: &dyn FrameSink,
    path: &CameraPath,
    timings: &[FrameTiming],
    warmup: Outcome,
) -> Report {
    let names: Vec<&str> = crate::renderer::all_passes()
        .iter()
        .map(|p| p.name())
        .collect();
    Report::new(
        &ctx.info,
        args.scene.size.0,
        args.scene.size.1,
        report_config(
            ctx,
            renderer,
            path,
            RunLength {
                fps: args.scene.fps,
                frames: args.frames,
                warmup,
            },
            sink.present_mode(),
        ),
        &names,
        timings,
        warmup.frames as u64,
    )
}

/// One configuration of a comparison: its renderer, its timings so far and its warmup.
struct Run {
    reuse: bool,
    renderer: Renderer,
    timings: Vec<FrameTiming>,
    warmup: Outcome,
}

/// `bench --compare-reuse`: both configurations on one context. Each warms up on its own;
/// the shorter warmup then continues along the path to the longer one's end, so both measure
/// the same path frames; the measured frames alternate between the two renderers, so a change
/// of the machine's speed during the run (lavapipe shares its cores) falls on both alike.
fn bench_compare_reuse(
    args: &BenchArgs,
    ctx: &Arc<Context>,
    sink: &mut dyn FrameSink,
    scene: Scene,
    path: CameraPath,
) -> Result<()> {
    let fps = args.scene.fps;
    let mut runs = Vec::new();
    for reuse in [true, false] {
        let mut config = args.scene.render_config();
        config.temporal.reuse = reuse;
        let mut renderer = Renderer::new(ctx, scene.clone(), config)?;
        sink.begin(&scene.name);
        let (timings, warmup) = warmup::run(&mut renderer, sink, &path, fps, args.warmup, true)?;
        eprintln!("reuse {}: {}", on_off(reuse), warmup.describe());
        runs.push(Run {
            reuse,
            renderer,
            timings,
            warmup,
        });
    }
    let first = runs.iter().map(|r| r.warmup.frames).max().unwrap_or(0);
    for run in &mut runs {
        let behind = first - run.warmup.frames;
        if behind > 0 {
            eprintln!(
                "reuse {}: {behind} more warmup frames to reach frame {first}",
                on_off(run.reuse)
            );
            let more = headless::run_from(
                &mut run.renderer,
                sink,
                &path,
                run.warmup.frames..first,
                fps,
                false,
                &mut |_| Ok(()),
            )?;
            run.timings.extend(more);
            run.warmup.frames = first;
        }
    }
    let base = scene.camera;
    let orbit = scene.orbit();
    let mut bar = Progress::new(2 * args.frames as u64, "rendering, interleaved", true);
    // Each frame polls for Ctrl-C: a signal stops the run between frames.
    let _scope = crate::interrupt::graceful();
    for i in first..first.saturating_add(args.frames) {
        let camera = path.camera_at(&base, &orbit, frame_time(i, fps));
        for run in &mut runs {
            run.renderer.set_time(frame_time(i, fps));
            run.timings.extend(sink.frame(&mut run.renderer, &camera)?);
            bar.inc();
        }
    }
    bar.finish();
    let mut reports = Vec::new();
    for run in &mut runs {
        run.timings.extend(run.renderer.finish()?);
        let report = report(
            args,
            ctx,
            &run.renderer,
            sink,
            &path,
            &run.timings,
            run.warmup,
        );
        println!("reuse {}:", on_off(run.reuse));
        print!("{}", report.table());
        if let (Some(out), true) = (&args.out, run.reuse) {
            headless::write_output(&mut run.renderer, out)?;
            eprintln!("wrote {}", out.display());
        }
        reports.push(report);
    }
    let [on, off]: [Report; 2] = reports
        .try_into()
        .map_err(|_| Error::Config("comparison needs two runs".into()))?;
    let comparison = Comparison::new("reuse", ["reuse on", "reuse off"], [on, off]);
    print!("{}", comparison.table());
    if let Some(json) = &args.json {
        write_json(json, &comparison)?;
    }
    Ok(())
}

/// `--explain`: the path's second frame as data, after its first.
fn explain(args: &BenchArgs, renderer: &mut Renderer, path: &CameraPath) -> Result<String> {
    let base = renderer.scene.camera;
    let orbit = renderer.scene.orbit();
    let times = (frame_time(0, args.scene.fps), frame_time(1, args.scene.fps));
    let first = path.camera_at(&base, &orbit, times.0);
    let second = path.camera_at(&base, &orbit, times.1);
    let moving = if first == second {
        "the camera still"
    } else {
        "the camera moving"
    };
    let (w, h) = args.scene.size;
    let header = format!(
        "frame 2 of {} at {w}x{h}, {moving}: the passes in recording order, with what each \
         declares it reads, writes and updates (reads and writes)\n",
        renderer.scene.name
    );
    Ok(header + &renderer.explain_frame((&first, &second), times)?)
}

fn on_off(reuse: bool) -> &'static str {
    if reuse {
        "on"
    } else {
        "off"
    }
}

pub fn bench(cli: &Cli, args: &BenchArgs) -> Result<()> {
    check_frames(args.frames, "--frames")?;
    if let Warmup::Frames(n) = args.warmup {
        check_frames(n, "--warmup")?;
    }
    if args.frames == 0 {
        return Err(Error::Config("--frames must be at least 1".into()));
    }
    if args.flicker && args.compare_reuse {
        return Err(Error::Config(
            "--flicker measures one run's frames: leave out --compare-reuse".into(),
        ));
    }
    // --explain prints the frame and measures nothing: a file it would not write is an error.
    if args.explain {
        for (given, option) in [
            (args.json.is_some(), "--json"),
            (args.out.is_some(), "--out"),
            (args.flicker, "--flicker"),
        ] {
            if given {
                return Err(Error::Config(format!(
                    "--explain prints the frame and exits without rendering the run: leave out \
                     {option}"
                )));
            }
        }
    }
    if let Some(json) = &args.json {
        crate::files::prepare_file(json, "--json")?;
    }
    if let Some(out) = &args.out {
        crate::files::prepare_png(out, "--out")?;
    }
    let (scene, path) = load(cli, &args.scene)?;
    let window = args.window.then(|| format!("ssgi bench: {}", scene.name));
    let (ctx, mut sink) = open_sink(window, args.scene.size, context_options(cli))?;
    // Before --compare-reuse: the frame as data is one renderer's, whatever the run would be.
    if args.explain {
        let mut renderer = Renderer::new(&ctx, scene, args.scene.render_config())?;
        print!("{}", explain(args, &mut renderer, &path)?);
        drop(renderer);
        drop(sink);
        return finish(&ctx);
    }
    if args.compare_reuse {
        bench_compare_reuse(args, &ctx, sink.as_mut(), scene, path)?;
        drop(sink);
        return finish(&ctx);
    }
    let mut renderer = Renderer::new(&ctx, scene, args.scene.render_config())?;
    if args.explain_skips {
        print!("{}", renderer.explain_skips());
    }
    let report = measure(args, &ctx, &mut renderer, sink.as_mut(), &path)?;
    print!("{}", report.table());
    if let Some(json) = &args.json {
        write_json(json, &report)?;
    }
    if let Some(out) = &args.out {
        headless::write_output(&mut renderer, out)?;
        eprintln!("wrote {}", out.display());
    }
    drop(renderer);
    drop(sink);
    finish(&ctx)
}
