//! Which graphics backend and adapter to render with.

use std::fmt;
use std::str::FromStr;

use crate::RenderError;

/// The graphics backend to render with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BackendChoice {
    /// The fastest adapter found on GL or Vulkan: a discrete GPU before an integrated one
    /// before a software rasterizer; between two adapters of the same kind, Vulkan on hardware
    /// and GL on a CPU (Mesa's llvmpipe renders about twice as fast as lavapipe).
    #[default]
    Auto,
    /// OpenGL / OpenGL ES through EGL (Mesa llvmpipe without a GPU).
    Gl,
    /// Vulkan (Mesa lavapipe without a GPU).
    Vulkan,
}

impl BackendChoice {
    /// The choice named by the `WGPU_BACKEND` environment variable (`gl`, `vulkan`, `auto`;
    /// wgpu also spells GL `gles` or `opengl`), or [`BackendChoice::Auto`] when it is unset
    /// or empty.
    pub fn from_env() -> Result<Self, RenderError> {
        match std::env::var("WGPU_BACKEND") {
            Ok(value) if !value.trim().is_empty() => value.parse(),
            _ => Ok(Self::Auto),
        }
    }

    /// The wgpu backend set searched for this choice.
    pub fn backends(self) -> wgpu::Backends {
        match self {
            Self::Auto => wgpu::Backends::GL | wgpu::Backends::VULKAN,
            Self::Gl => wgpu::Backends::GL,
            Self::Vulkan => wgpu::Backends::VULKAN,
        }
    }
}

impl FromStr for BackendChoice {
    type Err = RenderError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "" | "auto" | "gl,vulkan" | "vulkan,gl" => Ok(Self::Auto),
            "gl" | "gles" | "opengl" => Ok(Self::Gl),
            "vulkan" | "vk" => Ok(Self::Vulkan),
            other => Err(RenderError::UnknownBackend(other.to_owned())),
        }
    }
}

impl fmt::Display for BackendChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Auto => "auto",
            Self::Gl => "gl",
            Self::Vulkan => "vulkan",
        })
    }
}

/// Rank of an adapter for [`BackendChoice::Auto`]: higher is preferred.
pub(crate) fn adapter_rank(device_type: wgpu::DeviceType, backend: wgpu::Backend) -> u32 {
    let kind = match device_type {
        wgpu::DeviceType::DiscreteGpu => 40,
        wgpu::DeviceType::IntegratedGpu => 30,
        wgpu::DeviceType::VirtualGpu => 20,
        wgpu::DeviceType::Other => 10,
        wgpu::DeviceType::Cpu => 0,
    };
    let cpu = device_type == wgpu::DeviceType::Cpu;
    let backend = match (backend, cpu) {
        (wgpu::Backend::Gl, true) | (wgpu::Backend::Vulkan, false) => 2,
        (wgpu::Backend::Vulkan, true) | (wgpu::Backend::Gl, false) => 1,
        _ => 0,
    };
    kind + backend
}

/// A short human-readable list of the backends in a set, e.g. `gl, vulkan`.
pub(crate) fn backend_names(backends: wgpu::Backends) -> String {
    let mut names = Vec::new();
    if backends.contains(wgpu::Backends::GL) {
        names.push("gl");
    }
    if backends.contains(wgpu::Backends::VULKAN) {
        names.push("vulkan");
    }
    if names.is_empty() {
        "none".into()
    } else {
        names.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_backend_names_and_rejects_unknown_ones() {
        assert_eq!("GL".parse::<BackendChoice>().unwrap(), BackendChoice::Gl);
        assert_eq!(
            " vulkan ".parse::<BackendChoice>().unwrap(),
            BackendChoice::Vulkan
        );
        assert_eq!(
            "auto".parse::<BackendChoice>().unwrap(),
            BackendChoice::Auto
        );
        let err = "metal".parse::<BackendChoice>().unwrap_err();
        assert!(err.to_string().contains("metal"), "{err}");
    }

    #[test]
    fn auto_prefers_gpus_then_gl_on_cpu() {
        let llvmpipe = adapter_rank(wgpu::DeviceType::Cpu, wgpu::Backend::Gl);
        let lavapipe = adapter_rank(wgpu::DeviceType::Cpu, wgpu::Backend::Vulkan);
        let gpu = adapter_rank(wgpu::DeviceType::DiscreteGpu, wgpu::Backend::Vulkan);
        assert!(gpu > llvmpipe && llvmpipe > lavapipe);
    }
}
