//! The command line every lesson shares (INTERFACES.md).

use std::path::PathBuf;

use clap::Parser;

/// The most timed frames `--frames` accepts.
pub const MAX_FRAMES: u32 = 1000;

#[derive(Parser, Debug, Clone)]
#[command(about = "A lesson of the shadow workbook", disable_version_flag = true)]
pub struct Args {
    /// Render offscreen, write images and report.json, print the report table.
    #[arg(long)]
    pub headless: bool,
    /// A scene file (TOML); the lesson's default scene otherwise.
    #[arg(long, value_name = "FILE.toml")]
    pub scene: Option<PathBuf>,
    #[arg(long, default_value_t = 1280, value_parser = clap::value_parser!(u32).range(16..=8192))]
    pub width: u32,
    #[arg(long, default_value_t = 720, value_parser = clap::value_parser!(u32).range(16..=8192))]
    pub height: u32,
    /// Run only this variant (repeatable). Default: all of the lesson's variants.
    #[arg(long = "variant", value_name = "NAME")]
    pub variants: Vec<String>,
    /// Print the lesson's variants and exit.
    #[arg(long)]
    pub list_variants: bool,
    /// Timed frames per variant after warm-up (1 to 1000); the report quotes
    /// the median. 1000 frames of the slowest lesson on lavapipe take minutes.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=MAX_FRAMES as i64))]
    pub frames: u32,
    /// Output folder. Default: `out/<lesson>/`
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// vulkan | gl | metal | dx12 (WGPU_BACKEND is honoured too).
    #[arg(long)]
    pub backend: Option<String>,
    /// any (the default: your GPU if you have one) | software (lavapipe or
    /// llvmpipe, as the tests and the grader use) | part of an adapter's
    /// name. WORKBOOK_ADAPTER is honoured too.
    #[arg(long, value_name = "any|software|NAME")]
    pub adapter: Option<String>,
    /// The scene's depth-stencil format: auto (the default: Depth32FloatStencil8
    /// where the adapter has it, else Depth24PlusStencil8) | depth24plus-stencil8
    /// | depth32float-stencil8. WORKBOOK_DEPTH_FORMAT is honoured too.
    #[arg(long, value_name = "auto|depth24plus-stencil8|depth32float-stencil8")]
    pub depth_format: Option<String>,
}
