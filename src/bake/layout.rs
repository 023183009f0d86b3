//! The mip chain's level sizes and where each level starts in one flat array.

use super::input::BakeError;

/// Level sizes by the GPU rule (Vulkan, D3D, WebGPU): `w_(k+1) = max(1, floor(w_k / 2))`,
/// likewise the height, down to `1 x 1`, so a chain has `1 + floor(log2(max(w, h)))` levels.
/// Levels are stored one after the other, each row-major, in one slice of
/// [`ChainLayout::len`] texels: level `k` occupies `offset .. offset + width * height` of
/// [`ChainLayout::level`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChainLayout {
    width: usize,
    height: usize,
    levels: usize,
}

/// One level of a [`ChainLayout`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Level {
    /// Texels per row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// The index of its first texel in the chain's flat array.
    pub offset: usize,
}

impl Level {
    /// `width * height`.
    #[inline]
    pub const fn len(&self) -> usize {
        self.width * self.height
    }

    /// Whether the level holds no texel (never, for a level of a [`ChainLayout`]).
    #[inline]
    pub const fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The texels `rows` of this level within the chain's flat array.
    #[inline]
    pub const fn rows(&self, rows: core::ops::Range<usize>) -> core::ops::Range<usize> {
        self.offset + rows.start * self.width..self.offset + rows.end * self.width
    }
}

/// `max(1, n >> k)`: the GPU rule applied `k` times.
#[inline]
pub(crate) const fn level_size(n: usize, k: usize) -> usize {
    if k >= usize::BITS as usize {
        return 1;
    }
    let s = n >> k;
    if s == 0 { 1 } else { s }
}

impl ChainLayout {
    /// The chain of a `width x height` base level. `ZeroSize` for a zero dimension;
    /// `Length` when the chain's texel count overflows `usize`.
    pub fn new(width: usize, height: usize) -> Result<Self, BakeError> {
        if width == 0 || height == 0 {
            return Err(BakeError::ZeroSize);
        }
        let levels = 1 + (usize::BITS - 1 - width.max(height).leading_zeros()) as usize;
        let layout = Self {
            width,
            height,
            levels,
        };
        // The chain holds less than 4/3 of the base level plus one row and column per level.
        let mut total: usize = 0;
        for k in 0..levels {
            let n = level_size(width, k)
                .checked_mul(level_size(height, k))
                .and_then(|n| total.checked_add(n));
            total = n.ok_or(BakeError::Length {
                expected: usize::MAX,
                got: 0,
            })?;
        }
        Ok(layout)
    }

    /// The base level's width.
    #[inline]
    pub const fn width(&self) -> usize {
        self.width
    }

    /// The base level's height.
    #[inline]
    pub const fn height(&self) -> usize {
        self.height
    }

    /// The number of levels, `1 + floor(log2(max(width, height)))`.
    #[inline]
    pub const fn levels(&self) -> usize {
        self.levels
    }

    /// Level `k` (`k < levels()`; beyond, the `1 x 1` size at the end of the chain).
    pub const fn level(&self, k: usize) -> Level {
        let mut offset = 0;
        let mut j = 0;
        while j < k && j < self.levels {
            offset += level_size(self.width, j) * level_size(self.height, j);
            j += 1;
        }
        Level {
            width: level_size(self.width, k),
            height: level_size(self.height, k),
            offset,
        }
    }

    /// The texel count of the whole chain.
    pub const fn len(&self) -> usize {
        let last = self.level(self.levels - 1);
        last.offset + last.len()
    }

    /// Whether the chain is empty (never: a layout has at least one texel).
    pub const fn is_empty(&self) -> bool {
        false
    }

    /// The entries of scratch space a band bake needs: one accumulated row of the base
    /// level and one output row ([`super::bake_rows`]).
    #[inline]
    pub const fn scratch_len(&self) -> usize {
        2 * self.width
    }
}
