//! The exact box filter of GGX over slices (KHPL16 eq. 16, [`rect::d_rect`]).

use super::super::filter::rect;
use super::super::filter::rect::Tier;
use super::super::ndf::roughness::AxisAligned;
use super::lanes::{BLOCK, Body, atan2_upper_lane};
use super::{F, Vec2, Vec3};

/// The exact box-filtered GGX [`rect::d_rect`] (KHPL16 eq. 16: the mean of the GGX slope
/// density over the slope-domain rectangle `s(h_i) +/- (half_x[i], half_y[i])`, divided by
/// `h_z^4`; per steradian) for each half vector `h_i` and half extent:
/// `out[i] = d_rect(*r, h_i, (half_x[i], half_y[i]))`, **bit for bit**. The half extents are
/// the kernel as given (no clamps: pass rectangles already through `ClampRules::rect` for the
/// clamped route). Out of domain as [`rect::d_rect`] (`0` below the horizon and for NaN, never
/// NaN). Returns the number of elements written. Allocates nothing.
///
/// Vectorised where the scalar case analysis integrates both axes by Gauss-Legendre rules of
/// 2, 4 or 6 nodes (short sides against the distance to the integrand's poles: most pixel
/// footprints): per block, the elements of each pair of rules are gathered and evaluated by
/// one vector loop with that pair's rules; the closed form (long sides) runs the scalar path.
#[inline]
pub fn d_rect(
    r: &AxisAligned,
    hx: &[F],
    hy: &[F],
    hz: &[F],
    half_x: &[F],
    half_y: &[F],
    out: &mut [F],
) -> usize {
    let n = out
        .len()
        .min(hx.len())
        .min(hy.len())
        .min(hz.len())
        .min(half_x.len())
        .min(half_y.len());
    super::simd::dispatch(RectLoop {
        r: *r,
        ins: [&hx[..n], &hy[..n], &hz[..n], &half_x[..n], &half_y[..n]],
        out: &mut out[..n],
    });
    n
}

/// The tier pairs with a vector loop, in order: each its own loop with constant tiers.
const PAIRS: [(Tier, Tier); 9] = [
    (Tier::Gl2, Tier::Gl2),
    (Tier::Gl2, Tier::Gl4),
    (Tier::Gl2, Tier::Gl6),
    (Tier::Gl4, Tier::Gl2),
    (Tier::Gl4, Tier::Gl4),
    (Tier::Gl4, Tier::Gl6),
    (Tier::Gl6, Tier::Gl2),
    (Tier::Gl6, Tier::Gl4),
    (Tier::Gl6, Tier::Gl6),
];

/// The class of the elements with a long side (a tier `Closed`): the closed-form lane.
const CLOSED: u8 = PAIRS.len() as u8;
/// The class of the rest (the `f64` 8- and 10-point rules): the scalar path.
const REST: u8 = CLOSED + 1;

/// The class of an element's tiers: its index in [`PAIRS`], [`CLOSED`] or [`REST`].
#[inline(always)]
fn pair_index((tu, tv): (Tier, Tier)) -> u8 {
    let k = |t: Tier| match t {
        Tier::Gl2 => 0u8,
        Tier::Gl4 => 1,
        Tier::Gl6 => 2,
        Tier::Closed => 3,
        _ => 9,
    };
    let (a, b) = (k(tu), k(tv));
    if a < 3 && b < 3 {
        3 * a + b
    } else if a == 3 || b == 3 {
        CLOSED
    } else {
        REST
    }
}

/// The box filter's loop: per block, each element's tier pair (the scalar case analysis'
/// first step), then per pair the block's elements of that pair gathered into contiguous
/// columns and evaluated by one vector loop whose tiers are constants; the rest (and every
/// flagged element) by [`rect::d_rect`]. Buffers on the stack: allocates nothing.
struct RectLoop<'a> {
    r: AxisAligned,
    ins: [&'a [F]; 5],
    out: &'a mut [F],
}

impl Body for RectLoop<'_> {
    // Measured at 0.7 times the scalar loop on SSE2 (two `f64` lanes, the gather).
    const WIDE_ONLY: bool = true;

    #[inline(always)]
    fn go_scalar(self) {
        let Self { r, ins, out } = self;
        for (i, o) in out.iter_mut().enumerate() {
            *o = rect::d_rect(
                r,
                Vec3::new(ins[0][i], ins[1][i], ins[2][i]),
                Vec2::new(ins[3][i], ins[4][i]),
            );
        }
    }

    #[inline(always)]
    fn go(self) {
        let Self { r, ins, out } = self;
        let n = out.len();
        let ins = ins.map(|s| &s[..n]);
        let at = |i: usize| {
            (
                Vec3::new(ins[0][i], ins[1][i], ins[2][i]),
                Vec2::new(ins[3][i], ins[4][i]),
            )
        };
        let mut pair = [0u8; BLOCK];
        let mut idx = [0u16; BLOCK];
        let mut cols = [[0.0 as F; BLOCK]; 5];
        let mut vals = [0.0 as F; BLOCK];
        let mut slow = [false; BLOCK];
        let mut b = 0;
        while b < n {
            let e = n.min(b + BLOCK);
            let mut counts = [0usize; REST as usize + 1];
            for i in b..e {
                let (h, s) = at(i);
                let p = pair_index(rect::RectSetup::new(r, h, s).tiers);
                pair[i - b] = p;
                counts[p as usize] += 1;
            }
            // One vector loop per class: the class's elements gathered, the lane `$lane`
            // (of a `RectSetup`) over them, then the flagged ones by the scalar path.
            macro_rules! pass {
                ($k:expr, $lane:expr) => {
                    if counts[$k as usize] > 0 {
                        let m = gather(&ins, b, e, &pair, $k as u8, &mut idx, &mut cols);
                        for j in 0..m {
                            let h = Vec3::new(cols[0][j], cols[1][j], cols[2][j]);
                            let s = Vec2::new(cols[3][j], cols[4][j]);
                            let (v, sl) = $lane(rect::RectSetup::new(r, h, s));
                            vals[j] = v;
                            slow[j] = sl;
                        }
                        for j in 0..m {
                            let i = b + idx[j] as usize;
                            out[i] = if slow[j] {
                                let (h, s) = at(i);
                                rect::d_rect(r, h, s)
                            } else {
                                vals[j]
                            };
                        }
                    }
                };
            }
            // The Gauss-Legendre pairs, each with its tiers as constants (a macro, not a loop
            // over `PAIRS`: a loop that is not unrolled would leave them variables, and the
            // case analysis in the lane would stop the vectoriser).
            macro_rules! pairs {
                ($($k:literal)*) => {$(
                    pass!($k, |st: rect::RectSetup| st.lane(PAIRS[$k].0, PAIRS[$k].1));
                )*};
            }
            pairs!(0 1 2 3 4 5 6 7 8);
            // The closed form's lane (a long side): the four-edge form with the polynomial
            // `atan2`; the elements it does not take (far field, 1D closed form) flagged.
            pass!(CLOSED, |st: rect::RectSetup| st.closed_lane(atan2_upper_lane));
            if counts[REST as usize] > 0 {
                for i in b..e {
                    if pair[i - b] == REST {
                        let (h, s) = at(i);
                        out[i] = rect::d_rect(r, h, s);
                    }
                }
            }
            b = e;
        }
    }
}

/// Gathers the elements of block `b..e` whose pair is `k` into the first `m` entries of
/// `cols` (and their offsets into `idx`); returns `m`.
#[inline(always)]
fn gather(
    ins: &[&[F]; 5],
    b: usize,
    e: usize,
    pair: &[u8; BLOCK],
    k: u8,
    idx: &mut [u16; BLOCK],
    cols: &mut [[F; BLOCK]; 5],
) -> usize {
    let mut m = 0;
    for i in b..e {
        if pair[i - b] == k {
            idx[m] = (i - b) as u16;
            for (c, s) in cols.iter_mut().zip(ins) {
                c[m] = s[i];
            }
            m += 1;
        }
    }
    m
}
