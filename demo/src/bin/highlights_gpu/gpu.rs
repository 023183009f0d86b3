//! The adapter, render targets, read-back and GPU timing.

use filtered_ndf_gpu::harness::Choice;

/// The device of the adapter chosen by `FILTERED_NDF_GPU_BACKEND` (as the conformance
/// harness chooses it: a real GPU first, then Vulkan over GL), with timestamp queries where
/// the adapter has them.
pub struct Gpu {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub info: wgpu::AdapterInfo,
    /// Timestamp queries inside render passes are available.
    pub timestamps: bool,
}

impl Gpu {
    /// (The selection repeats the harness's private `open`, which requests no features:
    /// this device needs `TIMESTAMP_QUERY` where the adapter has it.)
    pub fn open(choice: Choice) -> Result<Self, String> {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        let backends = match choice {
            Choice::Vulkan => wgpu::Backends::VULKAN,
            Choice::Gl => wgpu::Backends::GL,
            Choice::Any => wgpu::Backends::VULKAN | wgpu::Backends::GL,
        };
        desc.backends = backends;
        let instance = wgpu::Instance::new(desc);
        let mut adapters = pollster::block_on(instance.enumerate_adapters(backends));
        if adapters.is_empty() {
            return Err(choice.missing_adapter_hint().to_string());
        }
        adapters.sort_by_key(|a| {
            let i = a.get_info();
            let kind = match i.device_type {
                wgpu::DeviceType::DiscreteGpu => 0,
                wgpu::DeviceType::IntegratedGpu => 1,
                wgpu::DeviceType::VirtualGpu => 2,
                wgpu::DeviceType::Cpu => 3,
                wgpu::DeviceType::Other => 4,
            };
            (kind, i.backend != wgpu::Backend::Vulkan)
        });
        let adapter = adapters.remove(0);
        let info = adapter.get_info();
        let wanted = wgpu::Features::TIMESTAMP_QUERY;
        let features = adapter.features() & wanted;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("highlights_gpu"),
            required_features: features,
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| {
            format!(
                "{info:?}: request_device failed: {e}{}",
                filtered_ndf_gpu::harness::device_failure_hint(&info)
            )
        })?;
        Ok(Self {
            device,
            queue,
            info,
            timestamps: features.contains(wgpu::Features::TIMESTAMP_QUERY),
        })
    }

    /// Backend, adapter, driver.
    pub fn label(&self) -> String {
        let i = &self.info;
        format!(
            "{:?}: {} ({} {})",
            i.backend, i.name, i.driver, i.driver_info
        )
    }

    /// A software rasteriser (Mesa's llvmpipe / lavapipe): absolute times mean little.
    pub fn is_software(&self) -> bool {
        self.info.device_type == wgpu::DeviceType::Cpu
    }

    /// Waits for the queue.
    pub fn wait(&self) -> Result<(), String> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| format!("poll: {e}"))
    }

    /// A `width x height` render target of four f32 values per pixel, held as their bits in
    /// `Rgba32Uint` (renderable on every backend, GL included), that can be read by
    /// `textureLoad` and copied out.
    pub fn target(&self, label: &str, width: u32, height: u32) -> wgpu::Texture {
        self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba32Uint,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        })
    }

    /// The RGB of a target of [`Gpu::target`], row by row from the top.
    pub fn read_rgb(&self, texture: &wgpu::Texture) -> Result<Vec<glam::Vec3>, String> {
        let (w, h) = (texture.width(), texture.height());
        let row = (w * 16).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
            * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("read-back"),
            size: (row * h) as u64,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = self.device.create_command_encoder(&Default::default());
        enc.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(row),
                    rows_per_image: Some(h),
                },
            },
            texture.size(),
        );
        self.queue.submit([enc.finish()]);
        let bytes = self.map(&buffer)?;
        let mut out = Vec::with_capacity((w * h) as usize);
        for y in 0..h as usize {
            let line: &[f32] = bytemuck::cast_slice(&bytes[y * row as usize..][..w as usize * 16]);
            out.extend(
                line.chunks_exact(4)
                    .map(|p| glam::Vec3::new(p[0], p[1], p[2])),
            );
        }
        Ok(out)
    }

    /// Maps `buffer` for reading after the work submitted so far, and copies it out.
    fn map(&self, buffer: &wgpu::Buffer) -> Result<Vec<u8>, String> {
        let slice = buffer.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        self.wait()?;
        rx.recv()
            .map_err(|e| format!("map: {e}"))?
            .map_err(|e| format!("map: {e}"))?;
        let out = slice
            .get_mapped_range()
            .map_err(|e| format!("mapped range: {e}"))?
            .to_vec();
        buffer.unmap();
        Ok(out)
    }
}

/// GPU time of groups of render passes: timestamp queries where the adapter has them,
/// otherwise the wall-clock time from submission to completion of each group.
pub struct Timer {
    queries: Option<(wgpu::QuerySet, wgpu::Buffer, wgpu::Buffer)>,
    period_ns: f64,
}

/// The most passes one timed group may hold.
const MAX_PASSES: u32 = 16;

impl Timer {
    pub fn new(gpu: &Gpu) -> Self {
        let queries = gpu.timestamps.then(|| {
            let set = gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass times"),
                ty: wgpu::QueryType::Timestamp,
                count: 2 * MAX_PASSES,
            });
            let size = 16 * MAX_PASSES as u64;
            let resolve = gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps"),
                size,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let read = gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps read"),
                size,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            (set, resolve, read)
        });
        Self {
            queries,
            period_ns: gpu.queue.get_timestamp_period() as f64,
        }
    }

    /// What the times measure.
    pub fn method(&self) -> &'static str {
        if self.queries.is_some() {
            "timestamp queries around the render passes"
        } else {
            "wall-clock time from submission to completion (no timestamp queries)"
        }
    }

    /// The timestamp writes of pass `k` of a group, if timing with queries.
    pub fn writes(&self, k: u32) -> Option<wgpu::RenderPassTimestampWrites<'_>> {
        assert!(k < MAX_PASSES);
        self.queries
            .as_ref()
            .map(|(set, _, _)| wgpu::RenderPassTimestampWrites {
                query_set: set,
                beginning_of_pass_write_index: Some(2 * k),
                end_of_pass_write_index: Some(2 * k + 1),
            })
    }

    /// Submits the passes `record` encodes (`passes` of them, each with `writes(k)`) and
    /// returns their total GPU time in seconds.
    pub fn time(
        &self,
        gpu: &Gpu,
        passes: u32,
        record: impl FnOnce(&mut wgpu::CommandEncoder),
    ) -> Result<f64, String> {
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        record(&mut enc);
        match &self.queries {
            Some((set, resolve, read)) => {
                enc.resolve_query_set(set, 0..2 * passes, resolve, 0);
                enc.copy_buffer_to_buffer(resolve, 0, read, 0, 16 * passes as u64);
                gpu.queue.submit([enc.finish()]);
                let bytes = gpu.map(read)?;
                let ticks: &[u64] = bytemuck::cast_slice(&bytes[..16 * passes as usize]);
                let total: u64 = ticks
                    .chunks_exact(2)
                    .map(|t| t[1].saturating_sub(t[0]))
                    .sum();
                Ok(total as f64 * self.period_ns * 1e-9)
            }
            None => {
                gpu.wait()?;
                let start = std::time::Instant::now();
                gpu.queue.submit([enc.finish()]);
                gpu.wait()?;
                Ok(start.elapsed().as_secs_f64())
            }
        }
    }
}
