//! The wgpu compute harness: one dispatch evaluates a WGSL snippet over many cases.
//!
//! The snippet is the body of a function `eval()` in a top-level shader that `#import`s the
//! modules it needs. Case `i` reads its inputs with `x(j)`, `x2(j)`, `x3(j)`, `x4(j)` (`f32`
//! and vectors starting at input slot `j`) and writes its outputs with `y(j, v)`, `y2`, `y3`,
//! `y4`. Inputs and outputs are flat `f32` storage buffers of `n_in` and `n_out` slots per
//! case. The shader is composed with naga_oil ([`crate::modules::compose`]) and handed to wgpu
//! as naga IR, as Bevy does.
//!
//! **What starts the GPU.** `FILTERED_NDF_GPU_BACKEND` selects the backend: `vulkan`, `gl`
//! (OpenGL / GLES through EGL, no window), or `any` (the default: wgpu picks among both).
//! Without a GPU, Mesa's software drivers serve: lavapipe for Vulkan (Debian package
//! `mesa-vulkan-drivers`) and llvmpipe for GL (`libegl1`, `libegl-mesa0`, `libgl1-mesa-dri`).
//! A missing adapter is an error whose message names the package to install; the
//! conformance tests fail on it, never skip.

use std::borrow::Cow;
use std::sync::{Mutex, OnceLock};
use wgpu::util::DeviceExt;

/// The environment variable that selects the backend.
pub const BACKEND_VAR: &str = "FILTERED_NDF_GPU_BACKEND";

/// Cases per workgroup.
const WORKGROUP: u32 = 64;

/// The backend requested through [`BACKEND_VAR`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Choice {
    /// Vulkan (lavapipe without a GPU).
    Vulkan,
    /// OpenGL / GLES through EGL (llvmpipe without a GPU).
    Gl,
    /// Whatever wgpu picks among Vulkan and GL.
    Any,
}

impl Choice {
    /// Reads [`BACKEND_VAR`] (unset or empty: [`Choice::Any`]).
    pub fn from_env() -> Result<Self, String> {
        match std::env::var(BACKEND_VAR).unwrap_or_default().as_str() {
            "" | "any" => Ok(Self::Any),
            "vulkan" | "vk" => Ok(Self::Vulkan),
            "gl" | "gles" | "opengl" => Ok(Self::Gl),
            other => Err(format!(
                "{BACKEND_VAR}={other}: expected `vulkan`, `gl` or `any`"
            )),
        }
    }

    fn backends(self) -> wgpu::Backends {
        match self {
            Self::Vulkan => wgpu::Backends::VULKAN,
            Self::Gl => wgpu::Backends::GL,
            Self::Any => wgpu::Backends::VULKAN | wgpu::Backends::GL,
        }
    }

    /// What to install when no adapter of this choice is found.
    pub fn missing_adapter_hint(self) -> &'static str {
        match self {
            Self::Vulkan => {
                "no Vulkan adapter found: without a GPU, install Mesa's software Vulkan driver \
                 (lavapipe): `apt-get install mesa-vulkan-drivers`"
            }
            Self::Gl => {
                "no OpenGL/EGL adapter found: without a GPU, install Mesa's EGL and software GL \
                 driver (llvmpipe): `apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri`"
            }
            Self::Any => {
                "no Vulkan or OpenGL adapter found: without a GPU, install Mesa's software \
                 drivers: `apt-get install mesa-vulkan-drivers` (Vulkan, lavapipe) or \
                 `apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri` (GL, llvmpipe)"
            }
        }
    }
}

/// An adapter, its device and queue.
pub struct Gpu {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// The adapter's description.
    pub info: wgpu::AdapterInfo,
    /// Serialises dispatches (the GL backend runs on one context).
    lock: Mutex<()>,
}

impl Gpu {
    /// A short label: backend, adapter name, driver.
    pub fn label(&self) -> String {
        let i = &self.info;
        format!(
            "{:?}: {} ({} {})",
            i.backend, i.name, i.driver, i.driver_info
        )
    }

    /// The backend's short name (`vulkan`, `gl`, ...).
    pub fn backend_name(&self) -> &'static str {
        match self.info.backend {
            wgpu::Backend::Vulkan => "vulkan",
            wgpu::Backend::Gl => "gl",
            wgpu::Backend::Metal => "metal",
            wgpu::Backend::Dx12 => "dx12",
            _ => "other",
        }
    }
}

fn open(choice: Choice) -> Result<Gpu, String> {
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
    desc.backends = choice.backends();
    let instance = wgpu::Instance::new(desc);
    let mut adapters = pollster::block_on(instance.enumerate_adapters(choice.backends()));
    if adapters.is_empty() {
        return Err(choice.missing_adapter_hint().to_string());
    }
    // Prefer a real GPU, then Vulkan over GL.
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
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("filtered-ndf conformance"),
        required_features: adapter.features() & wgpu::Features::FLOAT32_FILTERABLE,
        required_limits: adapter.limits(),
        ..Default::default()
    }))
    .map_err(|e| {
        format!(
            "{info:?}: request_device failed: {e}{}",
            device_failure_hint(&info)
        )
    })?;
    Ok(Gpu {
        device,
        queue,
        info,
        lock: Mutex::new(()),
    })
}

/// What a failed `request_device` most likely means, for its error message (empty where
/// nothing is known). wgpu 30's GL backend asks EGL for a desktop OpenGL 3.3 context wherever
/// EGL offers desktop OpenGL. Mesa's llvmpipe then gives its newest version (4.5), but
/// NVIDIA's driver (580, on an H200) gave 3.3 exactly, without compute shaders (OpenGL 4.3),
/// and `request_device` failed with "Parent device is lost".
pub fn device_failure_hint(info: &wgpu::AdapterInfo) -> &'static str {
    if info.backend == wgpu::Backend::Gl && info.driver_info.starts_with("3.") {
        "; this is a desktop OpenGL 3.x context (wgpu's GL backend asks EGL for OpenGL 3.3, and \
         this driver gave 3.3 exactly): compute shaders need OpenGL 4.3; use \
         FILTERED_NDF_GPU_BACKEND=vulkan on this machine"
    } else {
        ""
    }
}

/// The process-wide GPU of the backend chosen by [`BACKEND_VAR`] (opened on first use).
pub fn gpu() -> Result<&'static Gpu, String> {
    static GPU: OnceLock<Result<Gpu, String>> = OnceLock::new();
    GPU.get_or_init(|| open(Choice::from_env()?))
        .as_ref()
        .map_err(Clone::clone)
}

/// A WGSL snippet evaluated once per case (see the module docs).
#[derive(Clone, Debug)]
pub struct Kernel<'a> {
    /// The `#import` lines.
    pub imports: &'a str,
    /// The body of `fn eval()`.
    pub body: &'a str,
    /// Input slots (`f32`) per case.
    pub n_in: usize,
    /// Output slots (`f32`) per case.
    pub n_out: usize,
}

impl Kernel<'_> {
    /// The top-level shader: the imports, the buffers, the accessors and the entry point.
    pub fn shader(&self) -> String {
        let (ni, no) = (self.n_in, self.n_out);
        format!(
            "{imports}

@group(0) @binding(0) var<storage, read> harness_in: array<f32>;
@group(0) @binding(1) var<storage, read_write> harness_out: array<f32>;
var<private> harness_i: u32;

fn x(j: u32) -> f32 {{ return harness_in[harness_i * {ni}u + j]; }}
fn x2(j: u32) -> vec2<f32> {{ return vec2<f32>(x(j), x(j + 1u)); }}
fn x3(j: u32) -> vec3<f32> {{ return vec3<f32>(x(j), x(j + 1u), x(j + 2u)); }}
fn x4(j: u32) -> vec4<f32> {{ return vec4<f32>(x(j), x(j + 1u), x(j + 2u), x(j + 3u)); }}
fn y(j: u32, v: f32) {{ harness_out[harness_i * {no}u + j] = v; }}
fn y2(j: u32, v: vec2<f32>) {{ y(j, v.x); y(j + 1u, v.y); }}
fn y3(j: u32, v: vec3<f32>) {{ y(j, v.x); y(j + 1u, v.y); y(j + 2u, v.z); }}
fn y4(j: u32, v: vec4<f32>) {{ y(j, v.x); y(j + 1u, v.y); y(j + 2u, v.z); y(j + 3u, v.w); }}

fn eval() {{
{body}
}}

@compute @workgroup_size({WORKGROUP})
fn main(@builtin(global_invocation_id) id: vec3<u32>) {{
    let i = id.x + id.y * {stride}u;
    if i >= arrayLength(&harness_out) / {no}u {{
        return;
    }}
    harness_i = i;
    eval();
}}
",
            imports = self.imports,
            body = self.body,
            stride = ROW * WORKGROUP,
        )
    }
}

/// Workgroups per row of the dispatch grid.
const ROW: u32 = 1024;

/// Evaluates `kernel` on every case of `inputs` (`n_in` slots per case) and returns the
/// outputs (`n_out` slots per case).
pub fn run(kernel: &Kernel, inputs: &[f32]) -> Result<Vec<f32>, String> {
    assert!(kernel.n_in > 0 && kernel.n_out > 0);
    assert_eq!(inputs.len() % kernel.n_in, 0, "inputs: whole cases");
    let n = inputs.len() / kernel.n_in;
    if n == 0 {
        return Ok(Vec::new());
    }
    let module = crate::modules::compose(&kernel.shader(), "harness.wgsl")?;
    run_module(module, n, inputs, kernel.n_out)
}

/// One mip chain of float texels, level after level, each row-major with `channels` values
/// per texel (the layout of `filtered_ndf::bake::ChainLayout`, sizes by the GPU rule).
#[derive(Clone, Debug)]
pub struct TextureChain {
    /// The base level's width.
    pub width: u32,
    /// The base level's height.
    pub height: u32,
    /// `4` (`rgba*float`) or `1` (`r*float`).
    pub channels: u32,
    /// Every level's texels, level after level.
    pub texels: Vec<f32>,
}

/// The textures of the moment-chain checks, bound beside the buffers: `@binding(2)` the
/// RGBA chain, `@binding(3)` the one-channel chain, `@binding(4)` a sampler (linear
/// magnification, minification and mip filtering, clamped to the edge). Declare them in the
/// snippet's imports as `harness_moments`, `harness_moments_xy`, `harness_sampler`.
#[derive(Clone, Debug)]
pub struct Textures {
    /// The four-channel chain.
    pub rgba: TextureChain,
    /// The one-channel chain.
    pub r: TextureChain,
    /// Upload as `rgba16float` / `r16float` (the texels must be `f16` values) instead of
    /// `rgba32float` / `r32float` (filterable only with `float32-filterable`).
    pub half: bool,
}

/// The WGSL declarations of the bindings of [`Textures`], for a snippet's imports.
pub const TEXTURE_DECLARATIONS: &str = "@group(0) @binding(2) var harness_moments: texture_2d<f32>;
@group(0) @binding(3) var harness_moments_xy: texture_2d<f32>;
@group(0) @binding(4) var harness_sampler: sampler;";

/// Whether the adapter filters 32-bit float textures (`float32-filterable`).
pub fn float32_filterable() -> Result<bool, String> {
    Ok(gpu()?
        .device
        .features()
        .contains(wgpu::Features::FLOAT32_FILTERABLE))
}

/// [`run`] with [`Textures`] bound.
pub fn run_textured(
    kernel: &Kernel,
    inputs: &[f32],
    textures: &Textures,
) -> Result<Vec<f32>, String> {
    let n = inputs.len() / kernel.n_in;
    if n == 0 {
        return Ok(Vec::new());
    }
    let module = crate::modules::compose(&kernel.shader(), "harness.wgsl")?;
    run_module_with(module, n, inputs, kernel.n_out, Some(textures))
}

fn upload(gpu: &Gpu, c: &TextureChain, half: bool) -> wgpu::TextureView {
    let levels = 32 - c.width.max(c.height).leading_zeros();
    let format = match (c.channels, half) {
        (4, false) => wgpu::TextureFormat::Rgba32Float,
        (4, true) => wgpu::TextureFormat::Rgba16Float,
        (_, false) => wgpu::TextureFormat::R32Float,
        (_, true) => wgpu::TextureFormat::R16Float,
    };
    let bytes: Vec<u8> = if half {
        c.texels
            .iter()
            .flat_map(|&v| filtered_ndf::bake::f16::f16_from_f32(v).to_le_bytes())
            .collect()
    } else {
        bytemuck::cast_slice(&c.texels).to_vec()
    };
    let tex = gpu.device.create_texture_with_data(
        &gpu.queue,
        &wgpu::TextureDescriptor {
            label: Some("harness chain"),
            size: wgpu::Extent3d {
                width: c.width,
                height: c.height,
                depth_or_array_layers: 1,
            },
            mip_level_count: levels,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &bytes,
    );
    tex.create_view(&Default::default())
}

/// [`run`] with the shader built on the concatenated file (`shaders/generated/filtered_ndf.wgsl`
/// as generated now) instead of the naga_oil composition: the snippet's `alias::item`
/// references are rewritten to the concatenated names ([`crate::concat`]).
pub fn run_concatenated(kernel: &Kernel, inputs: &[f32]) -> Result<Vec<f32>, String> {
    let n = inputs.len() / kernel.n_in;
    let user = crate::concat::rewrite_user_shader(&kernel.shader())?;
    let source = format!("{}\n{user}", crate::generate::concatenated()?);
    let (module, _) = crate::generate::parse_and_validate(&source, "concatenated harness")?;
    run_module(module, n, inputs, kernel.n_out)
}

/// A compiled harness shader with its buffers, ready to dispatch.
struct Prepared {
    pipeline: wgpu::ComputePipeline,
    bind: wgpu::BindGroup,
    output: wgpu::Buffer,
    staging: wgpu::Buffer,
    size: u64,
    n: usize,
}

fn prepare(
    gpu: &Gpu,
    module: naga::Module,
    n: usize,
    inputs: &[f32],
    n_out: usize,
    textures: Option<&Textures>,
) -> Result<Prepared, String> {
    let device = &gpu.device;
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("harness"),
        source: wgpu::ShaderSource::Naga(Cow::Owned(module)),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("harness"),
        layout: None,
        module: &shader,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("in"),
        contents: bytemuck::cast_slice(inputs),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let size = (n * n_out * 4) as u64;
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("out"),
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("staging"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let views = textures.map(|t| (upload(gpu, &t.rgba, t.half), upload(gpu, &t.r, t.half)));
    let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("harness"),
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        mipmap_filter: wgpu::MipmapFilterMode::Linear,
        ..Default::default()
    });
    let mut entries = vec![
        wgpu::BindGroupEntry {
            binding: 0,
            resource: input.as_entire_binding(),
        },
        wgpu::BindGroupEntry {
            binding: 1,
            resource: output.as_entire_binding(),
        },
    ];
    if let Some((rgba, r)) = &views {
        entries.push(wgpu::BindGroupEntry {
            binding: 2,
            resource: wgpu::BindingResource::TextureView(rgba),
        });
        entries.push(wgpu::BindGroupEntry {
            binding: 3,
            resource: wgpu::BindingResource::TextureView(r),
        });
        entries.push(wgpu::BindGroupEntry {
            binding: 4,
            resource: wgpu::BindingResource::Sampler(&sampler),
        });
    }
    let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("harness"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &entries,
    });
    if let Some(e) = pollster::block_on(scope.pop()) {
        return Err(format!("{}: {e}", gpu.label()));
    }
    Ok(Prepared {
        pipeline,
        bind,
        output,
        staging,
        size,
        n,
    })
}

/// Dispatches a prepared shader once and waits for it (optionally copying the output to the
/// staging buffer).
fn dispatch(gpu: &Gpu, p: &Prepared, copy: bool) -> Result<(), String> {
    let device = &gpu.device;
    let groups = (p.n as u32).div_ceil(WORKGROUP);
    let (gx, gy) = (groups.min(ROW), groups.div_ceil(ROW));
    let mut enc = device.create_command_encoder(&Default::default());
    {
        let mut pass = enc.begin_compute_pass(&Default::default());
        pass.set_pipeline(&p.pipeline);
        pass.set_bind_group(0, &p.bind, &[]);
        pass.dispatch_workgroups(gx, gy, 1);
    }
    if copy {
        enc.copy_buffer_to_buffer(&p.output, 0, &p.staging, 0, p.size);
    }
    gpu.queue.submit([enc.finish()]);
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| format!("poll: {e}"))?;
    Ok(())
}

/// Wall-clock seconds of `runs` dispatches of a composed module (after one warm-up), each
/// submitted and waited for on its own: for throughput ratios between shaders run the same
/// way on the same adapter.
pub fn time_module(
    module: naga::Module,
    n: usize,
    inputs: &[f32],
    n_out: usize,
    runs: usize,
) -> Result<Vec<f64>, String> {
    let gpu = gpu()?;
    let _guard = gpu.lock.lock().unwrap_or_else(|e| e.into_inner());
    let p = prepare(gpu, module, n, inputs, n_out, None)?;
    dispatch(gpu, &p, false)?;
    let mut t = Vec::new();
    for _ in 0..runs {
        let start = std::time::Instant::now();
        dispatch(gpu, &p, false)?;
        t.push(start.elapsed().as_secs_f64());
    }
    Ok(t)
}

/// Runs the entry point `main` of a composed module (the layout of [`Kernel::shader`]) over
/// `n` cases.
pub fn run_module(
    module: naga::Module,
    n: usize,
    inputs: &[f32],
    n_out: usize,
) -> Result<Vec<f32>, String> {
    run_module_with(module, n, inputs, n_out, None)
}

fn run_module_with(
    module: naga::Module,
    n: usize,
    inputs: &[f32],
    n_out: usize,
    textures: Option<&Textures>,
) -> Result<Vec<f32>, String> {
    let gpu = gpu()?;
    let _guard = gpu.lock.lock().unwrap_or_else(|e| e.into_inner());
    let p = prepare(gpu, module, n, inputs, n_out, textures)?;
    dispatch(gpu, &p, true)?;
    let slice = p.staging.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| format!("poll: {e}"))?;
    rx.recv()
        .map_err(|e| format!("map: {e}"))?
        .map_err(|e| format!("map: {e}"))?;
    let out = {
        let view = slice
            .get_mapped_range()
            .map_err(|e| format!("mapped range: {e}"))?;
        bytemuck::cast_slice::<u8, f32>(&view).to_vec()
    };
    p.staging.unmap();
    Ok(out)
}
