//! Indirect light filtered by CCIPCA (Chen, Lei & Chang 2012, `--indirect-filter ccipca`): a
//! new noisy RSM gather of `--vpls` VPLs per pixel every frame, the k bases updated from it
//! one after another (each update's image-wide sums reduced on the GPU, so no frame waits for
//! the CPU), and the noisy image projected on the bases: by default on last frame's, before
//! the updates (`--ccipca-project`), then the bases smoothed for the next frame
//! (`--ccipca-basis-filter`). When the camera moves, the bases are first warped along the
//! reprojection and orthogonalized (section 3.4). The equations and the CPU model the passes
//! are checked against are in model.rs.

pub mod args;
pub mod config;
pub mod model;
pub mod sweep;

use super::effect::{
    every_pixel, float_image, Effect, EffectId, FrameInfo, Recording, Registration, Setup, TermKind,
};
use super::resolve::EffectResources;
use crate::config::{IndirectFilter, RenderConfig};
use crate::effects::ccipca::config::{
    CcipcaOrthogonalize, CcipcaProject, CcipcaStages, CcipcaWeighting,
};
use crate::effects::indirect::{params, NOISY, VPL_PARAMS};
use crate::error::Result;
use crate::passes::compute::{ComputePass, Dispatch, PassDecl};
use crate::passes::decl::{Bind, Slot, Use};
use crate::passes::{PassId, PassLayout};
use crate::reference::compose::Terms;
use crate::resources::targets::{Target, Targets};
use crate::shaders::{self, CcipcaPush};
use crate::vk::recorder::Recorder;
use crate::vk::{Buffer, Context, DescriptorPool, Image, Tracker};
use ash::vk;
use gpu_allocator::MemoryLocation;
use model::AMNESIC;
use std::sync::Arc;

/// The effect's name (`Effect::id`).
pub const ID: EffectId = EffectId::new("ccipca");

/// The effect's passes (timing rows and the scene inputs each reads).
pub mod pass {
    use crate::passes::pass_id::{Change, PassId};

    /// CCIPCA's input, the indirect light's noisy gather (with the update's partial sums).
    pub use crate::effects::indirect::pass::INDIRECT_NOISY;
    /// CCIPCA: the bases warped along the reprojection and orthogonalized (a moving camera).
    pub const CCIPCA_REPROJECT: PassId =
        PassId::new("ccipca_reproject", &[Change::Camera, Change::Config]);
    /// CCIPCA: every basis updated from the noisy image, in turn (image-wide sums on the GPU).
    pub const CCIPCA_UPDATE: PassId = PassId::new("ccipca_update", &[Change::Config]);
    /// CCIPCA: the noisy image projected on the updated bases.
    pub const CCIPCA_RECONSTRUCT: PassId = PassId::new("ccipca_reconstruct", &[Change::Config]);
    /// CCIPCA: the bases smoothed for the next frame (--ccipca-basis-filter).
    pub const CCIPCA_BASIS_FILTER: PassId =
        PassId::new("ccipca_basis_filter", &[Change::Camera, Change::Config]);

    /// Every pass the effect may record, in recording order.
    pub const ALL: &[PassId] = &[
        CCIPCA_REPROJECT,
        INDIRECT_NOISY,
        CCIPCA_UPDATE,
        CCIPCA_RECONSTRUCT,
        CCIPCA_BASIS_FILTER,
    ];

    /// The timing groups `bench --compare-reuse`, tables and sweeps compare (summed per frame):
    /// the indirect light's, which every way of making it shares.
    pub const GROUPS: &[(&str, &[PassId])] = &[("indirect", ALL)];
}

/// The projection on the bases: the indirect light the composite adds.
const FILTERED: Slot = Slot::Own("filtered");
/// k basis images, vec4 per pixel, basis-major (basis 0's a: the pixel's sample count).
const BASES: Slot = Slot::OwnBuffer("bases");
/// Per pixel: the residual (rgb) and the samples seen (a).
const RESIDUAL: Slot = Slot::OwnBuffer("residual");
/// `SUM_VEC4S` vec4 of partial sums per 16x16 group.
const PARTIALS: Slot = Slot::OwnBuffer("partials");
/// `SUM_VEC4S` vec4 of image-wide sums per basis.
const TOTALS: Slot = Slot::OwnBuffer("totals");
/// The other bases buffer: last frame's, which the warp reads.
const BASES_PREV: Slot = Slot::OwnBuffer("bases_prev");

/// Pixels per side of the groups whose partial sums are stored.
const GROUP_SIDE: u32 = 16;
/// Room for vec4 of sums per group and per basis (shaders/ccipca/ccipca.glsl's SUM_VEC4S).
const SUM_VEC4S: u64 = 9;
/// vec4 of sums of one basis update (UPDATE_SUM_VEC4S).
const UPDATE_SUM_VEC4S: u32 = 2;

/// vec4 holding the packed Gram matrix of `k` bases (gram_vec4s).
fn gram_vec4s(k: u32) -> u32 {
    (k * (k + 1) / 2).div_ceil(4)
}

const REPROJECT: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, Slot::GPositionPrev, Use::Sampled),
    Bind::new(3, Slot::GNormalPrev, Use::Sampled),
    Bind::new(4, Slot::GMotion, Use::Sampled),
    Bind::new(6, BASES, Use::BufferReadWrite),
    Bind::new(8, PARTIALS, Use::BufferWrite),
    Bind::new(11, BASES_PREV, Use::BufferRead),
];

const ORTHOGONALIZE: &[Bind] = &[
    Bind::new(6, BASES, Use::BufferReadWrite),
    Bind::new(9, TOTALS, Use::BufferRead),
];

const NOISY_GATHER: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, Slot::RsmPosition, Use::Sampled),
    Bind::new(3, Slot::RsmNormal, Use::Sampled),
    Bind::new(4, Slot::RsmFlux, Use::Sampled),
    Bind::new(5, NOISY, Use::StorageWrite),
    Bind::new(6, BASES, Use::BufferReadWrite),
    Bind::new(7, RESIDUAL, Use::BufferReadWrite),
    Bind::new(8, PARTIALS, Use::BufferWrite),
    Bind::new(params::BINDING, VPL_PARAMS, Use::BufferRead),
];

const SUMS: &[Bind] = &[
    Bind::new(8, PARTIALS, Use::BufferRead),
    Bind::new(9, TOTALS, Use::BufferWrite),
];

const UPDATE: &[Bind] = &[
    Bind::new(6, BASES, Use::BufferReadWrite),
    Bind::new(7, RESIDUAL, Use::BufferReadWrite),
    Bind::new(8, PARTIALS, Use::BufferWrite),
    Bind::new(9, TOTALS, Use::BufferRead),
];

const BASIS_FILTER: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(6, BASES, Use::BufferWrite),
    Bind::new(8, PARTIALS, Use::BufferWrite),
    Bind::new(11, BASES_PREV, Use::BufferRead),
];

/// The projection on last frame's bases (--ccipca-project before).
const PROJECT: &[Bind] = &[
    Bind::new(5, NOISY, Use::Sampled),
    Bind::new(6, BASES, Use::BufferRead),
    Bind::new(7, RESIDUAL, Use::BufferReadWrite),
    Bind::new(8, PARTIALS, Use::BufferWrite),
    Bind::new(9, TOTALS, Use::BufferRead),
    Bind::new(10, FILTERED, Use::StorageWrite),
];

const RECONSTRUCT: &[Bind] = &[
    Bind::new(5, NOISY, Use::Sampled),
    Bind::new(7, RESIDUAL, Use::BufferRead),
    Bind::new(10, FILTERED, Use::StorageWrite),
];

// Every pass, declared once (`PassDecl`): `layouts` and `Passes::new` both read these. Each
// is specialized for k bases.
const REPROJECT_PASS: PassDecl = PassDecl::new(
    pass::CCIPCA_REPROJECT,
    &shaders::CCIPCA_REPROJECT_COMP,
    REPROJECT,
);
const GRAM_PASS: PassDecl = PassDecl::new(
    pass::CCIPCA_REPROJECT,
    &shaders::CCIPCA_SUMS_COMP_GRAM,
    SUMS,
);
const ORTHOGONALIZE_PASS: PassDecl = PassDecl::new(
    pass::CCIPCA_REPROJECT,
    &shaders::CCIPCA_ORTHOGONALIZE_COMP,
    ORTHOGONALIZE,
);
const NOISY_PASS: PassDecl = PassDecl::new(
    pass::INDIRECT_NOISY,
    &shaders::INDIRECT_NOISY_COMP_CCIPCA,
    NOISY_GATHER,
);
const SUMS_PASS: PassDecl = PassDecl::new(pass::CCIPCA_UPDATE, &shaders::CCIPCA_SUMS_COMP, SUMS);
const UPDATE_PASS: PassDecl = PassDecl::new(
    pass::CCIPCA_UPDATE,
    &shaders::CCIPCA_UPDATE_COMP_UPDATE,
    UPDATE,
);
const PROJECT_PASS: PassDecl = PassDecl::new(
    pass::CCIPCA_RECONSTRUCT,
    &shaders::CCIPCA_UPDATE_COMP_PROJECT,
    PROJECT,
);
const RECONSTRUCT_PASS: PassDecl = PassDecl::new(
    pass::CCIPCA_RECONSTRUCT,
    &shaders::CCIPCA_RECONSTRUCT_COMP,
    RECONSTRUCT,
);
const BASIS_FILTER_PASS: PassDecl = PassDecl::new(
    pass::CCIPCA_BASIS_FILTER,
    &shaders::CCIPCA_BASIS_FILTER_COMP,
    BASIS_FILTER,
);
const PASSES: [&PassDecl; 9] = [
    &REPROJECT_PASS,
    &GRAM_PASS,
    &ORTHOGONALIZE_PASS,
    &NOISY_PASS,
    &SUMS_PASS,
    &UPDATE_PASS,
    &PROJECT_PASS,
    &RECONSTRUCT_PASS,
    &BASIS_FILTER_PASS,
];

pub const REGISTRATION: Registration = Registration {
    id: ID,
    switch: "indirect",
    enabled: |c| c.effects.indirect && c.indirect.filter == IndirectFilter::Ccipca,
    create: |s| Ok(Box::new(CcipcaEffect::new(s)?)),
    layouts,
    passes: pass::ALL,
    timing_groups: pass::GROUPS,
    sweep_keys: sweep::SWEEP_KEYS,
    ambient: false,
    views: &[],
    estimates: |_| Terms::INDIRECT,
    toggles: &[],
    recompute_mask: None,
};

fn layouts() -> Vec<PassLayout> {
    PASSES.iter().map(|d| d.layout()).collect()
}

/// The passes, bound to one of the two bases buffers as the current one.
struct Passes {
    reproject: ComputePass,
    /// The Gram matrix's sums and the orthogonalization's transform.
    gram: ComputePass,
    orthogonalize: ComputePass,
    noisy: ComputePass,
    sums: ComputePass,
    update: ComputePass,
    /// One basis of the projection on last frame's bases.
    project: ComputePass,
    reconstruct: ComputePass,
    /// Reads the other bases buffer, writes this one.
    basis_filter: ComputePass,
}

impl Passes {
    fn new(ctx: &Arc<Context>, pool: &DescriptorPool, bases: u32) -> Result<Self> {
        let pass = |d: &PassDecl| ComputePass::declared_with(ctx, pool, d, &[bases]);
        Ok(Self {
            reproject: pass(&REPROJECT_PASS)?,
            gram: pass(&GRAM_PASS)?,
            orthogonalize: pass(&ORTHOGONALIZE_PASS)?,
            noisy: pass(&NOISY_PASS)?,
            sums: pass(&SUMS_PASS)?,
            update: pass(&UPDATE_PASS)?,
            project: pass(&PROJECT_PASS)?,
            reconstruct: pass(&RECONSTRUCT_PASS)?,
            basis_filter: pass(&BASIS_FILTER_PASS)?,
        })
    }

    /// The same pipelines with their own descriptor sets.
    fn instance(&self, pool: &DescriptorPool) -> Result<Self> {
        let i = |p: &ComputePass| p.instance(pool, &format!("{} (other bases)", p.id.name()));
        Ok(Self {
            reproject: i(&self.reproject)?,
            gram: i(&self.gram)?,
            orthogonalize: i(&self.orthogonalize)?,
            noisy: i(&self.noisy)?,
            sums: i(&self.sums)?,
            update: i(&self.update)?,
            project: i(&self.project)?,
            reconstruct: i(&self.reconstruct)?,
            basis_filter: i(&self.basis_filter)?,
        })
    }

    fn all(&self) -> [&ComputePass; 9] {
        [
            &self.reproject,
            &self.gram,
            &self.orthogonalize,
            &self.noisy,
            &self.sums,
            &self.update,
            &self.project,
            &self.reconstruct,
            &self.basis_filter,
        ]
    }
}

/// Whether a frame ends by filtering the bases into the other buffer.
fn filters_bases(c: &RenderConfig) -> bool {
    c.ccipca.basis_filter > 0 && c.ccipca.stages == CcipcaStages::All
}

struct Sized {
    noisy: Image,
    filtered: Image,
    /// Two, so that the warp reads last frame's while it writes this frame's.
    bases: [Buffer; 2],
    residual: Buffer,
    partials: Buffer,
    totals: Buffer,
    groups: u32,
}

pub struct CcipcaEffect {
    /// `passes[i]` works on `bases[i]` (and warps from the other).
    passes: [Passes; 2],
    sized: Sized,
    /// Which bases buffer holds the latest bases: flips on every frame that warps, and on
    /// every frame that filters them.
    current: usize,
    /// The bases buffer this frame's updates work on.
    work: usize,
    /// The camera moved since last frame: this frame warps.
    warp: bool,
    push: CcipcaPush,
    /// Frames since the bases last restarted, up to the memory (`max_age`).
    age: u32,
    /// The noisy gather's parameters.
    vpl_params: Buffer,
}

impl CcipcaEffect {
    pub fn new(s: &mut Setup<'_>) -> Result<Self> {
        let first = Passes::new(s.ctx, s.pool, s.config.ccipca.bases)?;
        let second = first.instance(s.pool)?;
        Ok(Self {
            passes: [first, second],
            sized: Self::create_sized(s.ctx, s.config)?,
            current: 0,
            work: 0,
            warp: false,
            push: CcipcaPush::default(),
            age: 0,
            vpl_params: params::buffer(s.ctx, s.tracker, "ccipca.vpl_params", s.config)?,
        })
    }

    fn create_sized(ctx: &Arc<Context>, c: &RenderConfig) -> Result<Sized> {
        let image = |name: &str| float_image(ctx, name, c);
        let buffer = |name: &str, bytes: u64| {
            Buffer::new(
                ctx,
                name,
                bytes,
                vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_SRC,
                MemoryLocation::GpuOnly,
            )
        };
        let pixels = c.width as u64 * c.height as u64;
        let groups = c.width.div_ceil(GROUP_SIDE) * c.height.div_ceil(GROUP_SIDE);
        let vec4 = 16;
        let bases = c.ccipca.bases as u64 * pixels * vec4;
        Ok(Sized {
            noisy: image("ccipca.noisy")?,
            filtered: image("ccipca.filtered")?,
            bases: [
                buffer("ccipca.bases 0", bases)?,
                buffer("ccipca.bases 1", bases)?,
            ],
            residual: buffer("ccipca.residual", pixels * vec4)?,
            partials: buffer("ccipca.partials", groups as u64 * SUM_VEC4S * vec4)?,
            totals: buffer(
                "ccipca.totals",
                config::CcipcaConfig::MAX_BASES as u64 * SUM_VEC4S * vec4,
            )?,
            groups,
        })
    }

    fn own(&self) -> [(Slot, [&Image; 2]); 2] {
        let s = &self.sized;
        [
            (NOISY, [&s.noisy, &s.noisy]),
            (FILTERED, [&s.filtered, &s.filtered]),
        ]
    }

    /// The buffers with `bases[current]` as this frame's.
    fn buffers(&self, current: usize) -> [(Slot, &Buffer); 6] {
        let s = &self.sized;
        [
            (BASES, &s.bases[current]),
            (RESIDUAL, &s.residual),
            (PARTIALS, &s.partials),
            (TOTALS, &s.totals),
            (BASES_PREV, &s.bases[1 - current]),
            (VPL_PARAMS, &self.vpl_params),
        ]
    }

    /// The push constants with `basis` and `sum_vec4s` vec4 of sums.
    fn push_bytes(&self, basis: u32, sum_vec4s: u32) -> [u8; CcipcaPush::SIZE] {
        CcipcaPush {
            basis,
            sum_vec4s,
            ..self.push
        }
        .to_bytes()
    }

    /// The bases filtered into the other buffer, which the next frame starts from. Filtered
    /// bases lean towards each other: with `always`, they are orthogonalized from the Gram
    /// matrix the filter summed (sum_vec4s 0: it sums nothing), as after a warp.
    fn record_basis_filter(
        &self,
        info: &FrameInfo<'_>,
        r: &mut Recording<'_>,
        own: &[(Slot, [&Image; 2]); 2],
    ) {
        let other = 1 - self.work;
        let buffers = self.buffers(other);
        let res = EffectResources {
            targets: info.targets,
            temporal: None,
            own,
            own_buffers: &buffers,
        };
        let pixels = every_pixel(info);
        let always = info.config.ccipca.orthogonalize == CcipcaOrthogonalize::Always;
        let bases = info.config.ccipca.bases;
        let gram = self.push_bytes(0, if always { gram_vec4s(bases) } else { 0 });
        let filter = &self.passes[other];
        r.timed(pass::CCIPCA_BASIS_FILTER, |rec, tr| {
            filter
                .basis_filter
                .record(rec, tr, info.frame, &res, &gram, pixels);
            if always {
                filter
                    .gram
                    .record(rec, tr, info.frame, &res, &gram, Dispatch::Groups(1));
                filter
                    .orthogonalize
                    .record(rec, tr, info.frame, &res, &gram, pixels);
            }
        });
    }
}

impl Effect for CcipcaEffect {
    fn id(&self) -> EffectId {
        ID
    }

    fn passes(&self) -> &'static [PassId] {
        pass::ALL
    }

    fn resize(&mut self, ctx: &Arc<Context>, config: &RenderConfig) -> Result<()> {
        self.sized = Self::create_sized(ctx, config)?;
        (self.age, self.current, self.work) = (0, 0, 0);
        Ok(())
    }

    fn bind(&self, ctx: &Context, targets: &Targets) -> Result<()> {
        let own = self.own();
        for (current, passes) in self.passes.iter().enumerate() {
            let buffers = self.buffers(current);
            let res = EffectResources {
                targets,
                temporal: None,
                own: &own,
                own_buffers: &buffers,
            };
            for p in passes.all() {
                p.bind(ctx, &res)?;
            }
        }
        Ok(())
    }

    /// Every frame adds a sample until the memory is full; with unchanged inputs the bases
    /// then only wander with the noise, so the filter has settled.
    fn settling(&self, config: &RenderConfig) -> bool {
        // Without reuse the bases restart every frame: a frame is as good as the next.
        config.temporal.reuse && self.age < config.ccipca.max_age
    }

    fn prepare(&mut self, info: &FrameInfo<'_>) {
        let c = &info.config.ccipca;
        let restart = !info.reusing();
        self.warp = !restart && info.camera_moved;
        self.work = if self.warp {
            1 - self.current
        } else {
            self.current
        };
        self.current = if filters_bases(info.config) {
            1 - self.work
        } else {
            self.work
        };
        self.age = if restart {
            1
        } else {
            (self.age + 1).min(c.max_age)
        };
        self.push = CcipcaPush {
            basis: 0,
            groups: self.sized.groups,
            max_age: c.max_age,
            restart: restart as u32,
            amnesic: AMNESIC as f32,
            frames: self.age,
            per_pixel_bases: match c.weighting {
                CcipcaWeighting::PerPixel => c.bases,
                CcipcaWeighting::FirstBasis => 1,
                CcipcaWeighting::Uniform => 0,
            },
            sum_vec4s: UPDATE_SUM_VEC4S,
            filter_radius: c.basis_filter,
            new_pixel_vpls: c.new_pixel_vpls,
        };
    }

    fn reprojects(&self, _info: &FrameInfo<'_>) -> bool {
        false
    }

    fn record(&self, info: &FrameInfo<'_>, r: &mut Recording<'_>) {
        let (own, buffers) = (self.own(), self.buffers(self.work));
        let res = EffectResources {
            targets: info.targets,
            temporal: None,
            own: &own,
            own_buffers: &buffers,
        };
        let passes = &self.passes[self.work];
        let pixels = every_pixel(info);
        let sums = |basis, sum_vec4s| self.push_bytes(basis, sum_vec4s);
        let push = |basis| sums(basis, UPDATE_SUM_VEC4S);
        if self.warp {
            // Warp (storing the Gram matrix's partial sums), add them up, orthogonalize.
            let gram = sums(0, gram_vec4s(info.config.ccipca.bases));
            r.timed(pass::CCIPCA_REPROJECT, |rec, tr| {
                passes
                    .reproject
                    .record(rec, tr, info.frame, &res, &gram, pixels);
                passes
                    .gram
                    .record(rec, tr, info.frame, &res, &gram, Dispatch::Groups(1));
                passes
                    .orthogonalize
                    .record(rec, tr, info.frame, &res, &gram, pixels);
            });
        }
        if info.config.ccipca.stages == CcipcaStages::WarpOnly {
            return;
        }
        r.timed(pass::INDIRECT_NOISY, |rec, tr| {
            passes
                .noisy
                .record(rec, tr, info.frame, &res, &push(0), pixels)
        });
        let bases = info.config.ccipca.bases;
        // Each basis: its sums, then the pass that uses them.
        let chain = |pass: &ComputePass, rec: &Recorder<'_>, tr: &mut Tracker| {
            for basis in 0..bases {
                let bytes = push(basis);
                passes
                    .sums
                    .record(rec, tr, info.frame, &res, &bytes, Dispatch::Groups(1));
                pass.record(rec, tr, info.frame, &res, &bytes, pixels);
            }
        };
        let before = info.config.ccipca.project == CcipcaProject::Before;
        if before {
            r.timed(pass::CCIPCA_RECONSTRUCT, |rec, tr| {
                chain(&passes.project, rec, tr)
            });
        }
        r.timed(pass::CCIPCA_UPDATE, |rec, tr| {
            chain(&passes.update, rec, tr)
        });
        if !before {
            r.timed(pass::CCIPCA_RECONSTRUCT, |rec, tr| {
                passes
                    .reconstruct
                    .record(rec, tr, info.frame, &res, &push(0), pixels)
            });
        }
        if filters_bases(info.config) {
            self.record_basis_filter(info, r, &own);
        }
    }

    fn buffer(&self, name: &str) -> Option<&Buffer> {
        (name == "bases").then(|| &self.sized.bases[self.current])
    }

    fn term<'a>(&'a self, _targets: &'a Targets, _parity: usize) -> (TermKind, &'a Image) {
        (TermKind::VplIrradiance, &self.sized.filtered)
    }

    fn target(&self, target: Target, _parity: usize, _config: &RenderConfig) -> Option<&Image> {
        match target {
            Target::Indirect => Some(&self.sized.filtered),
            Target::IndirectNoisy => Some(&self.sized.noisy),
            _ => None,
        }
    }
}
