//! The [`Lesson`] trait: a lesson's technique (its variants, its
//! resources, the passes of one frame) and its [`Capabilities`]; what it
//! measures besides is its [`Instruments`](crate::run::instruments::Instruments).
//! The runners (headless in [`crate::run::headless`], interactive in
//! [`crate::run::window`]) do the rest, and both call the same
//! [`Lesson::render`], which draws into any [`FrameTargets`].

use anyhow::Result;
use clap::ValueEnum;

use crate::gpu::render::SceneGpu;
use crate::gpu::targets::FrameTargets;
use crate::gpu::Gpu;
use crate::measure::timing::Frame;
use crate::scene::Scene;

/// A lesson's technique: its variants, its resources, and the passes of
/// one frame. What the runners measure and show besides the image is the
/// lesson's [`Instruments`](crate::run::instruments::Instruments), in its
/// `harness.rs`.
pub trait Lesson: Sized + 'static {
    /// `"lesson_01"`.
    const NAME: &'static str;
    /// The default scene, as TOML text (built-in meshes only).
    const DEFAULT_SCENE: &'static str;
    /// The lesson's variants, in report order. `--variant NAME` and the
    /// report use the names clap's `ValueEnum` gives them.
    type Variant: ValueEnum + Copy + PartialEq + std::fmt::Debug + 'static;
    /// What the lesson draws right beyond the basics (lights with a size,
    /// a moving camera, a shifted frustum) and when it has counted a
    /// variant; the runner refuses, with one line, a scene that needs more.
    const CAPABILITIES: Capabilities = Capabilities::BASIC;

    /// Rejects scenes the lesson cannot render (one clear line).
    fn check_scene(_scene: &Scene) -> Result<()> {
        Ok(())
    }

    /// Creates the lesson's pipelines and resources.
    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self>;

    /// Records one frame of `variant` into `targets`, one named pass at a
    /// time. Wherever it builds a light's matrix it applies
    /// `scene.light_jitter` (the runner's `--fragile` sub-texel move of the
    /// maps: identity otherwise), and it reads the scene's camera each
    /// frame where [`Capabilities::camera_path`] says so.
    fn render(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: Self::Variant,
    ) -> Result<()>;
}

/// What a lesson can draw right beyond the basics, and when it has counted
/// a variant. The runner checks a scene against it before it opens the GPU.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Capabilities {
    /// Whether the lesson renders lights with a size (`radius`,
    /// `angular_radius_deg`): soft shadows, lesson 10. The runner refuses
    /// such a scene with one line for the lessons that keep `false`.
    pub area_lights: bool,
    /// Whether the lesson re-reads the camera on every [`Lesson::render`],
    /// so that a scene's `[camera_path]` (shimmer, chapter 09) is measured
    /// right. A lesson that caches camera-dependent state keeps `false`,
    /// and the runner refuses such a scene with one line.
    pub camera_path: bool,
    /// Whether the lesson draws a scene's `[camera] shift` (an off-centre
    /// frustum) right. Lessons that draw with the scene's camera matrices
    /// see it for free; one that rebuilds the frustum from `fov_y_deg` and
    /// the aspect alone sets `false`, and the runner refuses a shifted
    /// scene with one line.
    pub camera_shift: bool,
    /// The frame of a variant, from its first after another variant's, on
    /// which the lesson has counted it: 1 for a lesson that counts every
    /// frame, 2 for lessons 05–08, which count a variant's volumes on its
    /// second frame against the depth its first left. The runner draws
    /// that many untimed frames before it reads a variant's images and
    /// counters.
    pub counted_on_frame: u32,
}

impl Capabilities {
    /// Point and directional lights without a size, a still camera, the
    /// scene's camera matrices as they are; counted on a variant's first
    /// frame.
    pub const BASIC: Capabilities = Capabilities {
        area_lights: false,
        camera_path: false,
        camera_shift: true,
        counted_on_frame: 1,
    };
}

/// A variant's one-line doc comment (its `///` in the lesson), or "".
pub fn variant_doc<V: ValueEnum>(v: V) -> String {
    let help = v
        .to_possible_value()
        .and_then(|p| p.get_help().map(|h| h.to_string()));
    let help = help.unwrap_or_default();
    help.lines().next().unwrap_or("").to_string()
}

/// A variant's name, as `--variant` and the report spell it.
pub fn variant_name<V: ValueEnum>(v: V) -> String {
    v.to_possible_value()
        .map(|p| p.get_name().to_string())
        .unwrap_or_default()
}

/// The prefix of an exercise's variant name (`exercise_slope_bias`): the
/// student's code from the chapter's exercises, run only when asked for by
/// name (`--variant exercise_...`, or the grader).
pub const EXERCISE_PREFIX: &str = "exercise_";

/// Whether `v` is an exercise (its name starts with [`EXERCISE_PREFIX`]).
pub fn is_exercise<V: ValueEnum>(v: V) -> bool {
    variant_name(v).starts_with(EXERCISE_PREFIX)
}

/// Every variant of `L` a default run shows, in report order: the
/// lesson's own, without its exercises.
pub fn all_variants<L: Lesson>() -> Vec<L::Variant> {
    let all = L::Variant::value_variants().iter().copied();
    all.filter(|&v| !is_exercise(v)).collect()
}

/// The exercises of `L`'s chapter, in order.
pub fn exercise_variants<L: Lesson>() -> Vec<L::Variant> {
    let all = L::Variant::value_variants().iter().copied();
    all.filter(|&v| is_exercise(v)).collect()
}

/// The variants `--variant` asked for (all when none), by name.
pub fn select_variants<L: Lesson>(asked: &[String]) -> Result<Vec<L::Variant>> {
    if asked.is_empty() {
        return Ok(all_variants::<L>());
    }
    asked
        .iter()
        .map(|a| {
            L::Variant::from_str(a, false).map_err(|_| {
                let known: Vec<String> = L::Variant::value_variants()
                    .iter()
                    .map(|&v| variant_name(v))
                    .collect();
                anyhow::anyhow!(
                    "--variant: unknown variant {a:?} (known: {})",
                    known.join(", ")
                )
            })
        })
        .collect()
}
