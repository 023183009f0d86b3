//! The demonstrations of `filtered-ndf`: the scenes, camera, renderer, methods, metrics and
//! images shared by the CPU demonstration (`highlights`), the GPU demonstration
//! (`highlights_gpu`) and the trade table (`tradeoff`).
//!
//! The pipeline: [`scene`] (analytic surfaces) -> [`camera`] (rays and their differentials)
//! -> [`render`] (G-buffers, footprints, the reference) with [`methods`] (the filters under
//! comparison) -> [`metrics`] (what a viewer sees) -> [`image_out`] and [`plot`]; the scenes'
//! runs ([`normal_map`], [`temporal`]) and investigations ([`glints`], [`residual`]) on top.

pub mod bake_baselines;
pub mod bumpy;
pub mod camera;
pub mod floor_reference;
pub mod glints;
pub mod image_out;
pub mod methods;
pub mod metrics;
pub mod normal_map;
pub mod options;
pub mod parallel;
pub mod peaks;
pub mod plot;
pub mod render;
pub mod residual;
pub mod scene;
pub mod temporal;
