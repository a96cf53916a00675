//! Opening a device: the best-ranked adapter of the chosen backends, with every limit it offers.

use crate::backend::{adapter_rank, backend_names};
use crate::RenderError;

/// An open device, its queue and what the adapter says of itself.
pub(super) type OpenDevice = (wgpu::Device, wgpu::Queue, wgpu::AdapterInfo);

/// Opens the best-ranked adapter of `backends` (among equals, the first one enumerated) with
/// every limit it offers: large images, three colour targets.
pub(super) fn open(backends: wgpu::Backends) -> Result<OpenDevice, RenderError> {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
        backends,
        ..wgpu::InstanceDescriptor::new_without_display_handle()
    });
    let adapters = pollster::block_on(instance.enumerate_adapters(backends));
    let mut best: Option<(u32, wgpu::Adapter)> = None;
    for adapter in adapters {
        let info = adapter.get_info();
        let rank = adapter_rank(info.device_type, info.backend);
        if best.as_ref().is_none_or(|(r, _)| rank > *r) {
            best = Some((rank, adapter));
        }
    }
    let (_, adapter) = best.ok_or_else(|| RenderError::NoAdapter {
        backends: backend_names(backends),
        reason: "none was found".into(),
    })?;
    let info = adapter.get_info();
    let limits = adapter.limits();
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("scenethesis-render"),
        required_limits: limits,
        ..Default::default()
    }))
    .map_err(|source| RenderError::Device {
        adapter: format!("{} ({:?})", info.name, info.backend),
        source,
    })?;
    tracing::info!(adapter = %info.name, backend = ?info.backend, "renderer ready");
    Ok((device, queue, info))
}
