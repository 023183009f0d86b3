//! The shaders (composed with naga_oil over the crate's WGSL modules) and the passes of one
//! frame: visibility, then either the forward pass of one method, or the G-buffer and
//! lighting passes of one deferred convention or of one method on the moments route.

use crate::frame::{Rect, SceneUniform, sphere_scissors};
use crate::gpu::{Gpu, Timer};
use crate::methods::Method;
use crate::{camera::Camera, scene::Scene};
use naga_oil::compose::{ComposableModuleDescriptor, Composer, NagaModuleDescriptor};
use std::borrow::Cow;
use wgpu::util::DeviceExt;

/// The example's own WGSL: four modules and five top-level shaders.
const SCENE_WGSL: &str = include_str!("shaders/scene.wgsl");
const SHADING_WGSL: &str = include_str!("shaders/shading.wgsl");
const MOMENTS_WGSL: &str = include_str!("shaders/moments.wgsl");
const METHODS_WGSL: &str = include_str!("shaders/methods.wgsl");
const VISIBILITY_WGSL: &str = include_str!("shaders/visibility.wgsl");
const FORWARD_WGSL: &str = include_str!("shaders/forward.wgsl");
const GBUFFER_WGSL: &str = include_str!("shaders/gbuffer.wgsl");
const LIGHTING_WGSL: &str = include_str!("shaders/lighting.wgsl");
const LIGHTING_MOMENTS_WGSL: &str = include_str!("shaders/lighting_moments.wgsl");

/// Objects drawn per frame: the water (and sky), then the spheres.
const OBJECTS: usize = 6;

/// The methods `methods.wgsl`'s `filtered_d` shades, in its order: the first ten of
/// `Method::ALL` (the CPU demo's exact Gaussian-filtered GGX is not shaded on the GPU here).
pub const FORWARD: [Method; 10] = {
    use crate::methods::{Family, IsoVariant};
    [
        Method::Unfiltered(Family::Beckmann),
        Method::Unfiltered(Family::Ggx),
        Method::BeckmannParallelogram,
        Method::GgxRectExact,
        Method::GgxProxy,
        Method::Tk19Projected,
        Method::Tk21Projected,
        Method::Tk19Isotropic(IsoVariant::Max),
        Method::Tk19Isotropic(IsoVariant::Trace),
        Method::Tk19Isotropic(IsoVariant::Average),
    ]
};

/// How a frame is shaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Route {
    /// One pass: per light, the half vector's quad derivatives and the method's filter.
    Forward(Method),
    /// The forward pass of a footprint method (`Method::uses_footprint`) on the CPU demo's
    /// moments route (`FootprintRoute::Moments`, `shaders/moments.wgsl`): on the water the
    /// kernel of the slope moments over the pixel's Gaussian window plus the parallax, centred
    /// on the window's mean normal; on the spheres the ray-differential footprint. No quad
    /// derivative; the water scene only (its bumpy spheres have no such inputs here).
    Moments(Method),
    /// A G-buffer pass storing the roughness filtered by a convention of `presets::ALL`
    /// (`None`: unfiltered) from the normal's quad derivatives, then a lighting pass.
    Deferred(Option<usize>),
    /// [`Route::Moments`] in deferred shading: a G-buffer pass storing the water's windowed
    /// slope moments (independent of the light; `gbuffer.wgsl`'s `fs_moments`), then a
    /// lighting pass forming the method's kernel with the light's parallax
    /// (`lighting_moments.wgsl`). The same formulas at the same pixel centres as the forward
    /// moments route.
    DeferredMoments(Method),
}

impl Route {
    /// The index the shaders specialise on: `METHOD` of `forward.wgsl` and
    /// `lighting_moments.wgsl` (the index in [`FORWARD`], or 10 + a preset's) or
    /// `gbuffer.wgsl`'s `PRESET` (12: none).
    fn constant(self) -> u32 {
        match self {
            Route::Forward(Method::Preset(i)) => 10 + i as u32,
            Route::Forward(m) | Route::Moments(m) | Route::DeferredMoments(m) => FORWARD
                .iter()
                .position(|&x| x == m)
                .expect("a method of FORWARD")
                as u32,
            Route::Deferred(p) => p.map_or(12, |i| i as u32),
        }
    }

    /// Passes per frame.
    pub fn passes(self) -> u32 {
        match self {
            Route::Forward(_) | Route::Moments(_) => 1,
            Route::Deferred(_) | Route::DeferredMoments(_) => 2,
        }
    }
}

fn compose(c: &mut Composer, source: &str, name: &str) -> Result<wgpu::naga::Module, String> {
    c.make_naga_module(NagaModuleDescriptor {
        source,
        file_path: name,
        ..Default::default()
    })
    .map_err(|e| e.emit_to_string(c))
}

fn shader(gpu: &Gpu, module: wgpu::naga::Module, label: &str) -> wgpu::ShaderModule {
    gpu.device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Naga(Cow::Owned(module)),
        })
}

/// The pipelines (any image size) and the render targets of the current size.
pub struct Renderer {
    composer: Composer,
    scene: wgpu::Buffer,
    /// The scene uniform alone (the visibility pass writes the texture the others read).
    scene_only: wgpu::BindGroup,
    objects: Vec<wgpu::BindGroup>,
    bgl_scene_vis: wgpu::BindGroupLayout,
    bgl_lighting: wgpu::BindGroupLayout,
    bgl_lighting_moments: wgpu::BindGroupLayout,
    layout_objects: wgpu::PipelineLayout,
    layout_lighting_moments: wgpu::PipelineLayout,
    visibility: wgpu::RenderPipeline,
    lighting: wgpu::RenderPipeline,
    /// The deferred moments route's G-buffer pass (one for every method; built by
    /// [`Renderer::prepare`] when a route needs it).
    gbuffer_moments: Option<wgpu::RenderPipeline>,
    /// Per route, its pipeline (the deferred moments routes: their lighting pass).
    pipelines: Vec<(Route, wgpu::RenderPipeline)>,
    targets: Option<Targets>,
    scissors: Vec<Rect>,
}

/// The render targets of one image size and the bind groups that read them.
struct Targets {
    width: u32,
    height: u32,
    visibility: wgpu::TextureView,
    /// The G-buffer's targets; the fourth only on the deferred moments route (the window's
    /// slope moments).
    gbuffer: [wgpu::TextureView; 4],
    output: wgpu::Texture,
    output_view: wgpu::TextureView,
    scene_vis: wgpu::BindGroup,
    lighting_group: wgpu::BindGroup,
    lighting_moments_group: wgpu::BindGroup,
}

fn uniform_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn texture_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Uint,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

fn target(format: wgpu::TextureFormat) -> Option<wgpu::ColorTargetState> {
    Some(wgpu::ColorTargetState {
        format,
        blend: None,
        write_mask: wgpu::ColorWrites::ALL,
    })
}

/// Every render target: f32 values as their bits (GL cannot render to `Rgba32Float`).
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Uint;

fn pipeline(
    gpu: &Gpu,
    layout: &wgpu::PipelineLayout,
    (module, fragment): (&wgpu::ShaderModule, &str),
    targets: usize,
    label: &str,
) -> wgpu::RenderPipeline {
    let targets = vec![target(FORMAT); targets];
    gpu.device
        .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(label),
            layout: Some(layout),
            vertex: wgpu::VertexState {
                module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module,
                entry_point: Some(fragment),
                compilation_options: Default::default(),
                targets: &targets,
            }),
            multiview_mask: None,
            cache: None,
        })
}

impl Renderer {
    /// The shared pipelines; the per-route pipelines are built by [`Renderer::prepare`], the
    /// render targets by [`Renderer::resize`].
    pub fn new(gpu: &Gpu) -> Result<Self, String> {
        let mut composer = filtered_ndf_gpu::modules::composer()?;
        for (source, path) in [
            (SCENE_WGSL, "demo/src/bin/highlights_gpu/shaders/scene.wgsl"),
            (
                SHADING_WGSL,
                "demo/src/bin/highlights_gpu/shaders/shading.wgsl",
            ),
            (
                MOMENTS_WGSL,
                "demo/src/bin/highlights_gpu/shaders/moments.wgsl",
            ),
            (
                METHODS_WGSL,
                "demo/src/bin/highlights_gpu/shaders/methods.wgsl",
            ),
        ] {
            let added = composer.add_composable_module(ComposableModuleDescriptor {
                source,
                file_path: path,
                ..Default::default()
            });
            if let Err(e) = added {
                return Err(e.emit_to_string(&composer));
            }
        }
        let device = &gpu.device;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let scene = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("scene"),
            size: std::mem::size_of::<SceneUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bgl = |label: &str, entries: &[wgpu::BindGroupLayoutEntry]| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(label),
                entries,
            })
        };
        let bgl_scene = bgl("scene", &[uniform_entry(0)]);
        let bgl_scene_vis = bgl("scene+visibility", &[uniform_entry(0), texture_entry(1)]);
        let bgl_object = bgl("object", &[uniform_entry(0)]);
        let bgl_lighting = bgl(
            "lighting",
            &[
                uniform_entry(0),
                texture_entry(1),
                texture_entry(2),
                texture_entry(3),
            ],
        );
        let bgl_lighting_moments = bgl(
            "lighting+moments",
            &[
                uniform_entry(0),
                texture_entry(1),
                texture_entry(2),
                texture_entry(3),
                texture_entry(4),
            ],
        );
        let layout = |groups: &[Option<&wgpu::BindGroupLayout>]| {
            device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: None,
                bind_group_layouts: groups,
                immediate_size: 0,
            })
        };
        let layout_scene = layout(&[Some(&bgl_scene)]);
        let layout_objects = layout(&[Some(&bgl_scene_vis), Some(&bgl_object)]);
        let layout_lighting = layout(&[Some(&bgl_lighting)]);
        let layout_lighting_moments = layout(&[Some(&bgl_lighting_moments)]);

        let scene_only = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("scene"),
            layout: &bgl_scene,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: scene.as_entire_binding(),
            }],
        });
        let objects = (0..OBJECTS as u32)
            .map(|i| {
                let mut bytes = [0u32; 4];
                bytes[0] = i;
                let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("object"),
                    contents: bytemuck::cast_slice(&bytes),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("object"),
                    layout: &bgl_object,
                    entries: &[wgpu::BindGroupEntry {
                        binding: 0,
                        resource: buffer.as_entire_binding(),
                    }],
                })
            })
            .collect();

        let mut build = |source: &str, name: &str, layout: &wgpu::PipelineLayout| {
            let module = compose(&mut composer, source, name)?;
            let module = shader(gpu, module, name);
            Ok::<_, String>(pipeline(gpu, layout, (&module, "fs"), 1, name))
        };
        let visibility = build(VISIBILITY_WGSL, "visibility.wgsl", &layout_scene)?;
        let lighting = build(LIGHTING_WGSL, "lighting.wgsl", &layout_lighting)?;
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(format!("{}: {e}", gpu.label()));
        }
        Ok(Self {
            composer,
            scene,
            scene_only,
            objects,
            bgl_scene_vis,
            bgl_lighting,
            bgl_lighting_moments,
            layout_objects,
            layout_lighting_moments,
            visibility,
            lighting,
            gbuffer_moments: None,
            pipelines: Vec::new(),
            targets: None,
            scissors: Vec::new(),
        })
    }

    /// Render targets of `width x height` (kept if the size is unchanged).
    pub fn resize(&mut self, gpu: &Gpu, width: u32, height: u32) {
        if self
            .targets
            .as_ref()
            .is_some_and(|t| (t.width, t.height) == (width, height))
        {
            return;
        }
        let device = &gpu.device;
        let (scene, bgl_scene_vis, bgl_lighting) =
            (&self.scene, &self.bgl_scene_vis, &self.bgl_lighting);
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let visibility_texture = gpu.target("visibility", width, height);
        let visibility = view(&visibility_texture);
        let gbuffer_textures = ["normal+alpha", "position+alpha", "albedo", "slope moments"]
            .map(|label| gpu.target(label, width, height));
        let gbuffer = gbuffer_textures.each_ref().map(view);
        let output = gpu.target("output", width, height);
        let output_view = view(&output);

        let scene_vis = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("scene+visibility"),
            layout: bgl_scene_vis,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: scene.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&visibility),
                },
            ],
        });
        // The scene uniform and the first `n` G-buffer targets.
        let lighting = |label: &str, layout: &wgpu::BindGroupLayout, n: usize| {
            let entries: Vec<wgpu::BindGroupEntry> = std::iter::once(wgpu::BindGroupEntry {
                binding: 0,
                resource: scene.as_entire_binding(),
            })
            .chain(
                gbuffer[..n]
                    .iter()
                    .zip(1..)
                    .map(|(v, binding)| wgpu::BindGroupEntry {
                        binding,
                        resource: wgpu::BindingResource::TextureView(v),
                    }),
            )
            .collect();
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout,
                entries: &entries,
            })
        };
        let lighting_group = lighting("lighting", bgl_lighting, 3);
        let lighting_moments_group = lighting("lighting+moments", &self.bgl_lighting_moments, 4);
        self.targets = Some(Targets {
            width,
            height,
            visibility,
            gbuffer,
            output,
            output_view,
            scene_vis,
            lighting_group,
            lighting_moments_group,
        });
    }

    fn t(&self) -> &Targets {
        self.targets.as_ref().expect("Renderer::resize first")
    }

    /// Builds the pipeline of each route (each shader specialised on its method or preset
    /// by a constant, so that a method's time is its own code's).
    pub fn prepare(&mut self, gpu: &Gpu, routes: &[Route]) -> Result<(), String> {
        let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        for &route in routes {
            if self.pipelines.iter().any(|(r, _)| *r == route) {
                continue;
            }
            if matches!(route, Route::DeferredMoments(_)) && self.gbuffer_moments.is_none() {
                let source = format!("{GBUFFER_WGSL}\nconst PRESET: u32 = 12u;\n");
                let module = compose(&mut self.composer, &source, "gbuffer.wgsl")?;
                let label = "G-buffer of the moments route";
                let module = shader(gpu, module, label);
                let p = pipeline(gpu, &self.layout_objects, (&module, "fs_moments"), 4, label);
                self.gbuffer_moments = Some(p);
            }
            let (base, name, constant, targets) = match route {
                Route::Forward(_) | Route::Moments(_) => {
                    (FORWARD_WGSL, "forward.wgsl", "METHOD", 1)
                }
                Route::Deferred(_) => (GBUFFER_WGSL, "gbuffer.wgsl", "PRESET", 3),
                Route::DeferredMoments(_) => {
                    (LIGHTING_MOMENTS_WGSL, "lighting_moments.wgsl", "METHOD", 1)
                }
            };
            let mut source = format!("{base}\nconst {constant}: u32 = {}u;\n", route.constant());
            if let Route::Forward(_) | Route::Moments(_) = route {
                let moments = matches!(route, Route::Moments(_));
                source.push_str(&format!("const MOMENTS: bool = {moments};\n"));
            }
            let layout = match route {
                Route::DeferredMoments(_) => &self.layout_lighting_moments,
                _ => &self.layout_objects,
            };
            let module = compose(&mut self.composer, &source, name)?;
            let label = format!("{route:?}");
            let module = shader(gpu, module, &label);
            let p = pipeline(gpu, layout, (&module, "fs"), targets, &label);
            self.pipelines.push((route, p));
        }
        match pollster::block_on(scope.pop()) {
            Some(e) => Err(format!("{}: {e}", gpu.label())),
            None => Ok(()),
        }
    }

    /// Uploads the frame's scene and camera and runs the visibility pass.
    pub fn begin_frame(&mut self, gpu: &Gpu, scene: &Scene, cam: &Camera) -> Result<(), String> {
        let u = SceneUniform::new(scene, cam);
        gpu.queue
            .write_buffer(&self.scene, 0, bytemuck::bytes_of(&u));
        let t = self.t();
        let scissors = sphere_scissors(scene, cam, t.width, t.height);
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = begin(&mut enc, &[&t.visibility], None);
            pass.set_pipeline(&self.visibility);
            pass.set_bind_group(0, &self.scene_only, &[]);
            pass.draw(0..3, 0..1);
        }
        gpu.queue.submit([enc.finish()]);
        self.scissors = scissors;
        gpu.wait()
    }

    /// Records the passes of `route` into `enc` (timed by `timer` if given).
    pub fn record(&self, enc: &mut wgpu::CommandEncoder, route: Route, timer: Option<&Timer>) {
        let own = &self
            .pipelines
            .iter()
            .find(|(r, _)| *r == route)
            .expect("Renderer::prepare first")
            .1;
        // The pass that draws the objects, and the lighting pass of the deferred routes.
        let (objects, lighting) = match route {
            Route::Forward(_) | Route::Moments(_) => (own, None),
            Route::Deferred(_) => (own, Some((&self.lighting, &self.t().lighting_group))),
            Route::DeferredMoments(_) => (
                self.gbuffer_moments
                    .as_ref()
                    .expect("Renderer::prepare first"),
                Some((own, &self.t().lighting_moments_group)),
            ),
        };
        let writes = |k| timer.and_then(|t| t.writes(k));
        let t = self.t();
        let targets: Vec<&wgpu::TextureView> = match route {
            Route::Forward(_) | Route::Moments(_) => vec![&t.output_view],
            Route::Deferred(_) => t.gbuffer[..3].iter().collect(),
            Route::DeferredMoments(_) => t.gbuffer.iter().collect(),
        };
        {
            let mut pass = begin(enc, &targets, writes(0));
            pass.set_pipeline(objects);
            pass.set_bind_group(0, &t.scene_vis, &[]);
            for (i, group) in self.objects.iter().enumerate() {
                let (x, y, w, h) = match i {
                    0 => (0, 0, t.width, t.height),
                    _ => self.scissors.get(i - 1).copied().unwrap_or((0, 0, 0, 0)),
                };
                if w == 0 || h == 0 {
                    continue;
                }
                pass.set_scissor_rect(x, y, w, h);
                pass.set_bind_group(1, group, &[]);
                pass.draw(0..3, 0..1);
            }
        }
        if let Some((pipeline, group)) = lighting {
            let mut pass = begin(enc, &[&t.output_view], writes(1));
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, group, &[]);
            pass.draw(0..3, 0..1);
        }
    }

    /// Shades the current frame with `route` and reads the image back.
    pub fn render(&self, gpu: &Gpu, route: Route) -> Result<Vec<glam::Vec3>, String> {
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        self.record(&mut enc, route, None);
        gpu.queue.submit([enc.finish()]);
        gpu.read_rgb(&self.t().output)
    }

    /// The GPU time of the visibility pass (seconds), `timer`'s way.
    pub fn time_visibility(&self, gpu: &Gpu, timer: &Timer) -> Result<f64, String> {
        let t = self.t();
        timer.time(gpu, 1, |enc| {
            let mut pass = begin(enc, &[&t.visibility], timer.writes(0));
            pass.set_pipeline(&self.visibility);
            pass.set_bind_group(0, &self.scene_only, &[]);
            pass.draw(0..3, 0..1);
        })
    }
}

fn begin<'a>(
    enc: &'a mut wgpu::CommandEncoder,
    targets: &[&wgpu::TextureView],
    timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'a>>,
) -> wgpu::RenderPass<'a> {
    let attachments: Vec<Option<wgpu::RenderPassColorAttachment>> = targets
        .iter()
        .map(|view| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })
        })
        .collect();
    enc.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: None,
        color_attachments: &attachments,
        depth_stencil_attachment: None,
        timestamp_writes,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}
