//! The statistics of a mip texel: weighted averages over its footprint on the base level,
//! accumulated in `f64` directly from the base texels (not from the level below, so no
//! level's storage format rounds another's input).

use super::input::{BakeError, SlopeSource, Texels};
use super::layout::{ChainLayout, level_size};
use crate::math as m;
use glam::{DVec2, DVec3};

/// Which base texels a mip texel averages, and with what weights (per axis; the 2-D weight
/// is the product).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kernel {
    /// The box that GPU mip generators use: level `k + 1` texel `i` averages texels `2i` and
    /// `2i + 1` of level `k` (a level of size 1 is copied), so an odd level's last row or
    /// column is dropped. On the base level: the aligned block of `2^k` texels starting at
    /// `i 2^k` (`2^min(k, floor(log2 n))` along an axis of `n` texels). Equal to [`Kernel::Area`]
    /// for power-of-two sizes.
    GpuBox,
    /// The texel's exact footprint: level-`k` texel `i` covers `[i n / n_k, (i + 1) n / n_k]`
    /// of the base axis (`n` texels, `n_k` at level `k`), each base texel weighted by the
    /// length of its overlap. Between consecutive levels of odd size `2m + 1` this is the
    /// three-tap filter with weights `((m - i), m, (i + 1)) / (2m + 1)`. Weights are integer
    /// overlaps divided once by `n` (each within half an ulp).
    Area,
}

/// The base texels `lo..hi` of mip texel `i` along an axis of `n` base texels at level `k`,
/// and the weight of base texel `t` in it.
#[derive(Clone, Copy, Debug)]
struct AxisFootprint {
    lo: usize,
    hi: usize,
    /// Area: the footprint `[i n, (i + 1) n]` in units of `1 / n_k`; GpuBox: unused.
    a: u64,
    b: u64,
    nk: u64,
    /// `1 / n` (Area) or `1 / block` (GpuBox).
    inv: f64,
    area: bool,
}

impl AxisFootprint {
    fn new(kernel: Kernel, n: usize, k: usize, i: usize) -> Self {
        match kernel {
            Kernel::GpuBox => {
                let halvings = k.min((usize::BITS - 1 - n.leading_zeros()) as usize);
                let block = 1usize << halvings;
                Self {
                    lo: i * block,
                    hi: i * block + block,
                    a: 0,
                    b: 0,
                    nk: 0,
                    inv: 1.0 / block as f64,
                    area: false,
                }
            }
            Kernel::Area => {
                let nk = level_size(n, k) as u64;
                let (a, b) = (i as u64 * n as u64, (i as u64 + 1) * n as u64);
                Self {
                    lo: (a / nk) as usize,
                    hi: b.div_ceil(nk) as usize,
                    a,
                    b,
                    nk,
                    inv: 1.0 / n as f64,
                    area: true,
                }
            }
        }
    }

    #[inline(always)]
    fn weight(&self, t: usize) -> f64 {
        if self.area {
            let (t0, t1) = (t as u64 * self.nk, (t as u64 + 1) * self.nk);
            (t1.min(self.b) - t0.max(self.a)) as f64 * self.inv
        } else {
            self.inv
        }
    }
}

/// The base roughness the texels' normals carry (the lobe each texel's normal is the centre
/// of).
#[derive(Clone, Copy, Debug)]
pub enum BaseRoughness<'a> {
    /// One `alpha` for every texel.
    Constant(f64),
    /// A roughness texture of the normal map's size.
    Texture(RoughnessMap<'a>),
}

/// A checked roughness texture: channel `channel` of `channels`, as `alpha` or as glTF's
/// perceptual roughness `r` (`alpha = r^2`).
#[derive(Clone, Copy, Debug)]
pub struct RoughnessMap<'a> {
    texels: Texels<'a>,
    width: usize,
    height: usize,
    channels: usize,
    channel: usize,
    perceptual: bool,
}

impl<'a> RoughnessMap<'a> {
    /// Checks the length, the channel, and every value: finite and in `[0, 1]` (`Unorm`
    /// always are), as `alpha` or perceptual roughness.
    pub fn new(
        texels: Texels<'a>,
        width: usize,
        height: usize,
        channels: usize,
        channel: usize,
        perceptual: bool,
    ) -> Result<Self, BakeError> {
        if channel >= channels {
            return Err(BakeError::Channels(channels));
        }
        if width == 0 || height == 0 {
            return Err(BakeError::ZeroSize);
        }
        let expected = width.saturating_mul(height).saturating_mul(channels);
        if texels.len() != expected {
            return Err(BakeError::Length {
                expected,
                got: texels.len(),
            });
        }
        if let Texels::F32(v) = texels {
            for (t, px) in v.chunks_exact(channels).enumerate() {
                let r = px[channel];
                if !(0.0..=1.0).contains(&r) {
                    return Err(BakeError::OutOfRange {
                        x: t % width,
                        y: t / width,
                        value: r as f64,
                    });
                }
            }
        }
        Ok(Self {
            texels,
            width,
            height,
            channels,
            channel,
            perceptual,
        })
    }

    /// `alpha^2` of texel `(x, y)`.
    #[inline(always)]
    fn alpha2(&self, x: usize, y: usize) -> f64 {
        let v = match self.texels {
            Texels::Unorm8(t) => {
                t[(y * self.width + x) * self.channels + self.channel] as f64 / 255.0
            }
            Texels::Unorm16(t) => {
                t[(y * self.width + x) * self.channels + self.channel] as f64 / 65535.0
            }
            Texels::F32(t) => t[(y * self.width + x) * self.channels + self.channel] as f64,
        };
        let a = if self.perceptual { v * v } else { v };
        a * a
    }
}

impl BaseRoughness<'_> {
    /// Checks a constant `alpha` (finite, in `(0, 1e4]`) or a texture's size against the
    /// source's.
    pub fn check(&self, width: usize, height: usize) -> Result<(), BakeError> {
        match *self {
            BaseRoughness::Constant(a) => {
                if !(a > 0.0 && a <= 1e4) {
                    return Err(BakeError::Parameter("alpha", a));
                }
            }
            BaseRoughness::Texture(t) => {
                if t.width != width || t.height != height {
                    return Err(BakeError::Length {
                        expected: width * height,
                        got: t.width * t.height,
                    });
                }
            }
        }
        Ok(())
    }
}

/// What a bake reads besides the map.
#[derive(Clone, Copy, Debug)]
pub struct Settings<'a> {
    /// The mip kernel.
    pub kernel: Kernel,
    /// The lobe each texel's normal carries.
    pub base: BaseRoughness<'a>,
}

/// A mip texel's statistics: weighted means over its footprint, in `f64`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TexelStats {
    /// `E[s]`, the first slope moments (LEAN's `B` with the opposite sign).
    pub mean: DVec2,
    /// `(E[s_x^2], E[s_x s_y], E[s_y^2])`, the second slope moments.
    pub second: DVec3,
    /// `E[n]`, the mean unit normal (its length `<= 1` is what Toksvig's factor reads).
    pub normal: DVec3,
    /// `E[alpha^2]`, the mean squared base roughness.
    pub alpha2: f64,
}

impl TexelStats {
    /// `w` times a base texel's slope moments and normal added in (`alpha2` apart).
    #[inline(always)]
    fn add(&mut self, w: f64, s: DVec2, n: DVec3) {
        let ws = w * s;
        self.mean += ws;
        self.second += DVec3::new(ws.x * s.x, ws.x * s.y, ws.y * s.y);
        self.normal += w * n;
    }

    #[inline(always)]
    fn add_scaled(&mut self, w: f64, o: &TexelStats) {
        self.mean += w * o.mean;
        self.second += w * o.second;
        self.normal += w * o.normal;
        self.alpha2 += w * o.alpha2;
    }

    /// The slope covariance `E[s s^T] - E[s] E[s]^T` as `(c11, c12, c22)` (LEAN eq. 5),
    /// projected to positive semi-definite (negative variances from rounding to `0`,
    /// `|c12| <= sqrt(c11 c22)`).
    pub fn covariance(&self) -> (f64, f64, f64) {
        let m = self.mean;
        let c11 = (self.second.x - m.x * m.x).max(0.0);
        let c22 = (self.second.z - m.y * m.y).max(0.0);
        let lim = m::sqrt(c11 * c22);
        let c12 = (self.second.y - m.x * m.y).clamp(-lim, lim);
        (c11, c12, c22)
    }
}

/// Row `row` of level `level`: each texel's [`TexelStats`] over its footprint on the base
/// level by the settings' kernel, into `out[..level width]`. `scratch` holds at least the base
/// width (one row of column sums). The base roughness must have passed
/// [`BaseRoughness::check`]. Sums are plain `f64` additions: a texel averaging `p` rows of
/// `q` columns carries at most `(p - 1) + (q - 1)` additions per value, so each mean is
/// within `(p + q) eps_f64` of the exact weighted mean of the decoded texels, relative to the
/// mean of their absolute values.
pub fn footprint_row<S: SlopeSource>(
    source: &S,
    settings: &Settings<'_>,
    layout: &ChainLayout,
    level: usize,
    row: usize,
    scratch: &mut [TexelStats],
    out: &mut [TexelStats],
) -> Result<(), BakeError> {
    let (w, h) = (layout.width(), layout.height());
    if source.width() != w || source.height() != h {
        return Err(BakeError::Length {
            expected: w * h,
            got: source.width() * source.height(),
        });
    }
    let lv = layout.level(level);
    if row >= lv.height {
        return Err(BakeError::Output {
            expected: row + 1,
            got: lv.height,
        });
    }
    if scratch.len() < w {
        return Err(BakeError::Output {
            expected: w,
            got: scratch.len(),
        });
    }
    if out.len() < lv.width {
        return Err(BakeError::Output {
            expected: lv.width,
            got: out.len(),
        });
    }
    let (kernel, base) = (settings.kernel, &settings.base);
    let fy = AxisFootprint::new(kernel, h, level, row);
    let scratch = &mut scratch[..w];
    // The column sums are needed only where some texel of this level reads them.
    let used = AxisFootprint::new(kernel, w, level, lv.width - 1).hi;
    scratch[..used].fill(TexelStats::default());
    let constant = match *base {
        BaseRoughness::Constant(a) => Some(a * a),
        BaseRoughness::Texture(_) => None,
    };
    for y in fy.lo..fy.hi {
        let wy = fy.weight(y);
        let row = scratch[..used].iter_mut().enumerate();
        match base {
            BaseRoughness::Texture(t) => {
                for (x, acc) in row {
                    let (s, n) = source.texel(x, y);
                    acc.add(wy, s, n);
                    acc.alpha2 += wy * t.alpha2(x, y);
                }
            }
            BaseRoughness::Constant(_) => {
                for (x, acc) in row {
                    let (s, n) = source.texel(x, y);
                    acc.add(wy, s, n);
                }
            }
        }
    }
    for (i, o) in out[..lv.width].iter_mut().enumerate() {
        let fx = AxisFootprint::new(kernel, w, level, i);
        let mut t = TexelStats::default();
        for (x, acc) in scratch[fx.lo..fx.hi].iter().enumerate() {
            t.add_scaled(fx.weight(fx.lo + x), acc);
        }
        if let Some(a2) = constant {
            t.alpha2 = a2;
        }
        *o = t;
    }
    Ok(())
}
