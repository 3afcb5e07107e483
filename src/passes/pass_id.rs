//! `PassId`: the typed name of every pass (timing rows, command labels, debug names) and the
//! scene inputs it reads. The frame's own passes are declared here; each effect declares its
//! passes in its folder, and `renderer::all_passes` puts them in recording order.

/// A pass: its name (the timing report's row, the command label, the pipelines' debug name)
/// and the scene inputs it reads itself (`inputs`). No two passes share a name
/// (`tests/reflection.rs`).
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct PassId {
    name: &'static str,
    inputs: &'static [Change],
}

impl std::fmt::Debug for PassId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name)
    }
}

/// A scene input whose change makes passes run again (`renderer::dependencies`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Change {
    /// The camera's view-projection or eye.
    Camera,
    /// The lights: the spot light (position, axis, cone, intensity, depth range) and the
    /// ambient radiance.
    Light,
    /// A moving object's transform (for the light view: one the light's frustum meets).
    Object,
    /// The configuration (the viewer's in-place switches; other changes rebuild).
    Config,
}

impl Change {
    pub const ALL: [Change; 4] = [
        Change::Camera,
        Change::Light,
        Change::Object,
        Change::Config,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Change::Camera => "camera",
            Change::Light => "light",
            Change::Object => "moving objects",
            Change::Config => "configuration",
        }
    }
}

impl PassId {
    /// Reflective shadow map + shadow depth from the spot light (only when light/geometry change).
    pub const LIGHT_VIEW: PassId = PassId::new("light_view", &[Change::Light, Change::Object]);
    /// Camera G-buffer MRT (with `--gbuffer visibility`: each pixel's triangle).
    pub const GBUFFER: PassId = PassId::new("gbuffer", &[Change::Camera, Change::Object]);
    /// `--gbuffer visibility`: the G-buffer rebuilt from each pixel's triangle.
    pub const GBUFFER_RESOLVE: PassId =
        PassId::new("gbuffer_resolve", &[Change::Camera, Change::Object]);
    /// Reverse reprojection: disocclusion test, history resampling, work list.
    pub const REPROJECT: PassId = PassId::new(
        "reproject",
        &[
            Change::Camera,
            Change::Light,
            Change::Object,
            Change::Config,
        ],
    );
    /// Composite + tonemap into the output image (display-linear for antialiasing).
    pub const COMPOSITE: PassId = PassId::new("composite", &[Change::Light, Change::Config]);

    /// The viewer's overlay over the presented frame (recorded in the window's frame hook;
    /// not a renderer pass, so not in `renderer::all_passes`).
    pub const OVERLAY: PassId = PassId::new("overlay", &[]);

    /// The frame's passes recorded before the effects', in recording order.
    pub const BEFORE_EFFECTS: [PassId; 4] = [
        PassId::LIGHT_VIEW,
        PassId::GBUFFER,
        PassId::GBUFFER_RESOLVE,
        PassId::REPROJECT,
    ];

    pub const fn new(name: &'static str, inputs: &'static [Change]) -> PassId {
        PassId { name, inputs }
    }

    pub fn name(self) -> &'static str {
        self.name
    }

    /// The scene inputs the pass reads itself: the frame block's camera and light members its
    /// shaders use, the objects it draws (or whose motion it follows), the configuration. What
    /// it reads of other passes' outputs comes from its resource declaration (`PassLayout::
    /// binds`); `renderer::dependencies` puts the two together, and `tests/dependencies.rs`
    /// checks this list against the frame members each compute shader names.
    pub fn inputs(self) -> &'static [Change] {
        self.inputs
    }
}
