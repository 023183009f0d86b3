// The visibility pass (the stand-in for the rasteriser's depth test): per pixel, the object
// seen and the distance of the water layer (`scene::visibility`). The forward and G-buffer
// passes read it instead of marching the height field again. Render targets hold f32 values
// as their bits in `rgba32uint` (every backend renders to it; GL's cannot render `rgba32float`).

#import highlights::scene

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    return scene::fullscreen(i);
}

@fragment
fn fs(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<u32> {
    return bitcast<vec4<u32>>(scene::visibility(scene::ray_dir(frag.xy)));
}
