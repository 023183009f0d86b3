//! The CPU demonstration's options, shared by its scenes and investigations.

use crate::methods::Method;
use crate::render::FootprintRoute;
use std::path::PathBuf;

/// Command-line options.
#[derive(Clone)]
pub struct Options {
    pub width: usize,
    pub height: usize,
    pub spp: usize,
    pub frames: usize,
    pub out: PathBuf,
    pub methods: Vec<Method>,
    pub route: FootprintRoute,
    pub threads: usize,
    pub seed: u64,
    pub exposure: f32,
    /// Also shade the engine presets (table only).
    pub presets: bool,
    /// Run the false-glint investigation (`glints.rs`).
    pub investigate: bool,
    /// Which scenes: the water (`water`), the normal-mapped floor (`normal-map`), the bumpy
    /// spheres (`bumpy`), or all three (`all`).
    pub scene: &'static str,
    /// Also score the footprint methods on the routes of the false-glint fix
    /// ([`FIX_ROUTES`]), still frame and temporal test.
    pub fix: bool,
}

/// The routes of the false-glint fix, scored beside `o.route` (still frame and temporal test):
/// the windowed moments, the two cheaper fixes of their Gaussian shape (2x2 sub-footprints,
/// the fourth-moment split), and the 4x4 traced sub-windows.
pub const FIX_ROUTES: [FootprintRoute; 4] = [
    FootprintRoute::Moments,
    FootprintRoute::SubFootprints,
    FootprintRoute::KurtosisSplit,
    FootprintRoute::SubWindows,
];
