//! Which adapter, backend and depth-stencil format a run opens: the
//! flags (`--adapter`, `--backend`, `--depth-format`) and their
//! environment variables, parsed, with the lines a wrong value gets.

use anyhow::{anyhow, bail, Result};

/// Which adapter to open (`--adapter`, else `WORKBOOK_ADAPTER`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum AdapterChoice {
    /// The system's preferred (high-performance) adapter: a real GPU if
    /// there is one. The default.
    Any,
    /// A software rasteriser (lavapipe, llvmpipe): what CI pins, so that
    /// its runs repeat to the fragment.
    Software,
    /// The first adapter whose name contains this text (any case).
    Named(String),
}

impl AdapterChoice {
    /// Parses `any`, `software` or a name fragment.
    pub fn parse(text: &str) -> Result<AdapterChoice> {
        match text.trim().to_ascii_lowercase().as_str() {
            "" => bail!("--adapter: empty (expected any, software or part of an adapter's name)"),
            "any" => Ok(AdapterChoice::Any),
            "software" | "cpu" => Ok(AdapterChoice::Software),
            name => Ok(AdapterChoice::Named(name.to_string())),
        }
    }

    /// `--adapter` if given, else `WORKBOOK_ADAPTER`, else [`AdapterChoice::Any`].
    pub fn from_flag_or_env(flag: Option<&str>) -> Result<AdapterChoice> {
        match flag {
            Some(f) => AdapterChoice::parse(f),
            None => match std::env::var("WORKBOOK_ADAPTER") {
                Ok(v) if !v.trim().is_empty() => {
                    AdapterChoice::parse(&v).map_err(|e| anyhow!("WORKBOOK_ADAPTER: {e}"))
                }
                _ => Ok(AdapterChoice::Any),
            },
        }
    }

    pub(crate) fn accepts(&self, info: &wgpu::AdapterInfo) -> bool {
        match self {
            AdapterChoice::Any => true,
            AdapterChoice::Software => info.device_type == wgpu::DeviceType::Cpu,
            AdapterChoice::Named(n) => info.name.to_ascii_lowercase().contains(n),
        }
    }
}

/// Which depth-stencil format the scene uses (`--depth-format`, else
/// `WORKBOOK_DEPTH_FORMAT`). wgpu's `Depth24PlusStencil8` is 24-bit unorm
/// where the driver has it and 32-bit float where it does not, so
/// [`crate::gpu::depth_probe`] asks the adapter what it stores.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthFormatChoice {
    /// `Depth32FloatStencil8` where the adapter has it, else
    /// `Depth24PlusStencil8`. The default.
    Auto,
    Depth24PlusStencil8,
    Depth32FloatStencil8,
}

impl DepthFormatChoice {
    /// Parses `auto`, `depth24plus-stencil8` or `depth32float-stencil8`
    /// (any case; wgpu's names, `Depth24PlusStencil8`, are accepted too).
    pub fn parse(text: &str) -> Result<DepthFormatChoice> {
        let key: String = text
            .trim()
            .to_ascii_lowercase()
            .chars()
            .filter(|c| !matches!(c, '-' | '_'))
            .collect();
        match key.as_str() {
            "auto" => Ok(DepthFormatChoice::Auto),
            "depth24plusstencil8" => Ok(DepthFormatChoice::Depth24PlusStencil8),
            "depth32floatstencil8" => Ok(DepthFormatChoice::Depth32FloatStencil8),
            _ => bail!(
                "unknown depth format {:?} (expected auto, depth24plus-stencil8 or depth32float-stencil8)",
                text.trim()
            ),
        }
    }

    /// `--depth-format` if given, else `WORKBOOK_DEPTH_FORMAT`, else
    /// [`DepthFormatChoice::Auto`]. Also returns where the choice came
    /// from, for error messages.
    pub fn from_flag_or_env(flag: Option<&str>) -> Result<(DepthFormatChoice, &'static str)> {
        match flag {
            Some(f) => DepthFormatChoice::parse(f)
                .map(|c| (c, "--depth-format"))
                .map_err(|e| anyhow!("--depth-format: {e}")),
            None => match std::env::var("WORKBOOK_DEPTH_FORMAT") {
                Ok(v) if !v.trim().is_empty() => DepthFormatChoice::parse(&v)
                    .map(|c| (c, "WORKBOOK_DEPTH_FORMAT"))
                    .map_err(|e| anyhow!("WORKBOOK_DEPTH_FORMAT: {e}")),
                _ => Ok((DepthFormatChoice::Auto, "--depth-format")),
            },
        }
    }

    /// The format on `adapter`, which has `features`; asking for
    /// `Depth32FloatStencil8` where it is missing is an error naming
    /// `source` (the flag or the variable) and the feature.
    pub fn resolve(
        self,
        features: wgpu::Features,
        source: &str,
        adapter: &str,
    ) -> Result<wgpu::TextureFormat> {
        let has_d32 = features.contains(wgpu::Features::DEPTH32FLOAT_STENCIL8);
        Ok(match self {
            DepthFormatChoice::Auto if has_d32 => wgpu::TextureFormat::Depth32FloatStencil8,
            DepthFormatChoice::Auto | DepthFormatChoice::Depth24PlusStencil8 => {
                wgpu::TextureFormat::Depth24PlusStencil8
            }
            DepthFormatChoice::Depth32FloatStencil8 if has_d32 => {
                wgpu::TextureFormat::Depth32FloatStencil8
            }
            DepthFormatChoice::Depth32FloatStencil8 => bail!(
                "{source} depth32float-stencil8: the adapter {adapter} lacks the DEPTH32FLOAT_STENCIL8 feature; use depth24plus-stencil8 or auto"
            ),
        })
    }
}

/// The line printed when `--adapter software` finds none.
pub const NO_SOFTWARE_ADAPTER_HINT: &str = "no GPU adapter found that is a software rasteriser (--adapter software, which CI pins): on Linux install Mesa's lavapipe/llvmpipe with `apt-get install -y mesa-vulkan-drivers libgl1-mesa-dri libegl1`; on Windows and macOS, or to use your GPU, pass --adapter any (WORKBOOK_ADAPTER=any), the default";

/// Parses a `--backend` value (also used for `WGPU_BACKEND`).
pub fn parse_backend(name: &str) -> Result<wgpu::Backends> {
    match name.trim().to_ascii_lowercase().as_str() {
        "vulkan" | "vk" => Ok(wgpu::Backends::VULKAN),
        "gl" | "gles" | "opengl" => Ok(wgpu::Backends::GL),
        "metal" | "mtl" => Ok(wgpu::Backends::METAL),
        "dx12" | "d3d12" => Ok(wgpu::Backends::DX12),
        other => bail!("--backend: unknown backend {other:?} (expected vulkan, gl, metal or dx12)"),
    }
}
