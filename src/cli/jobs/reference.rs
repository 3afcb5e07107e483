//! `ssgi reference`: the CPU ground truth of one frame, written as OpenEXR + previews.

use super::common::load_spec;
use crate::cli::args::{Cli, ReferenceArgs};
use crate::error::{Error, Result};
use crate::reference::run::Session;
use crate::reference::store::default_dir;
use crate::reference::{AoDefinition, RefBuffer, Settings};

pub fn reference(cli: &Cli, args: &ReferenceArgs) -> Result<()> {
    crate::files::prepare_dir(&args.out, "--out")?;
    let (scene, path) = load_spec(cli, &args.scene, &args.path)?;
    let frame = args.frame.unwrap_or(args.frames - 1);
    if frame >= args.frames {
        return Err(Error::Config(format!(
            "--frame {frame} is outside a {}-frame run (0..={})",
            args.frames,
            args.frames - 1
        )));
    }
    let time = crate::scene::path::frame_time(frame, args.fps);
    let camera = path.camera_at(&scene.camera, &scene.orbit(), time);
    // Moving objects and light where the frame has them.
    let scene = scene.posed(time);
    crate::reference::trace::check_light_radius(args.light_radius, scene.bounds().radius())
        .map_err(Error::Config)?;
    let settings = Settings {
        ao: AoDefinition {
            radius: args.ao_radius * scene.bounds().radius().max(f32::MIN_POSITIVE),
            attenuation: args.ao_attenuation,
        },
        light_radius: args.light_radius,
        seed: 1,
    };
    let cache = (!args.no_cache).then(|| args.cache_dir.clone().unwrap_or_else(default_dir));
    if let Some(dir) = &cache {
        crate::files::prepare_dir(dir, "--cache-dir")?;
    }
    let (w, h) = args.size;
    let start = std::time::Instant::now();
    let mut session = Session::start(&scene, camera, w, h, settings, cache, true)?;
    if session.from_cache {
        eprintln!("reference cache hit ({})", session.key);
    }
    session.ensure(RefBuffer::Ao, args.ao_samples / 2)?;
    session.ensure(RefBuffer::Direct, args.shadow_samples / 2)?;
    session.ensure(RefBuffer::Indirect, args.indirect_samples / 2)?;
    session.save()?;
    let json = crate::reference::output::write_all(&session, &args.out)?;
    eprintln!(
        "reference of {} at {w}x{h}: {:.1} s here, {:.2} Mrays/s on {} threads; standard error \
         ao {:.2e}, indirect {:.2e} (relative {:.2e}); wrote {}",
        scene.name,
        start.elapsed().as_secs_f64(),
        session.reference.rays_per_second() / 1e6,
        rayon::current_num_threads(),
        json["buffers"]["ao"]["standard_error"]
            .as_f64()
            .unwrap_or(f64::NAN),
        json["buffers"]["indirect"]["standard_error"]
            .as_f64()
            .unwrap_or(f64::NAN),
        json["buffers"]["indirect"]["relative_standard_error"]
            .as_f64()
            .unwrap_or(f64::NAN),
        args.out.display()
    );
    Ok(())
}
