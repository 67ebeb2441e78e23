//! Section "The balls' basins": where the balls end when they start from each pair of angles.
//! Not computed in the report: each point of a basin map is a whole run in time, so the section
//! says so in one line and names the command that computes them (`autobal basins`).

use super::{Ctx, Section};
use anyhow::Result;

/// Grid points per angle of `autobal basins` (its default `--n`).
const BASIN_N: usize = 24;

pub fn build(ctx: &Ctx) -> Result<Option<Section>> {
    let why = if ctx.spatial.is_none() {
        "the basins of `autobal basins` are of the spatial rotor's balls; this config has only a [planar] rotor".to_string()
    } else {
        format!(
            "not computed in the report: a basin map is {n} × {n} = {} runs in time of this rotor at a fixed speed, each as long as the run-up, i.e. hundreds of run-ups; compute it with `autobal basins --config FILE` (a [drive] at the speed of interest, e.g. kind = \"speed\" with omega0 at the operating speed)",
            BASIN_N * BASIN_N,
            n = BASIN_N
        )
    };
    Ok(Some(Section::not_applicable("basins", "The balls' basins", why)))
}
