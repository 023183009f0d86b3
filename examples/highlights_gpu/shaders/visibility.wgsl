// The visibility pass (the stand-in for the rasteriser's depth test): per pixel, the object
// seen and the distance of the water layer (`scene::visibility`). The forward and G-buffer
// passes read it instead of marching the height field again. Render targets hold f32 values
// as their bits in `rgba32uint` (every backend renders to it; GL's cannot render `rgba32float`).

#import highlights::scene

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<u32> {
    return bitcast<vec4<u32>>(scene::visibility(scene::ray_dir(frag.xy)));
}
