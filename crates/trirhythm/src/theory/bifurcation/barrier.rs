//! Energy-barrier surfaces ΔU_i over a parameter plane (Fig. 9).

use super::grid::Plane;
use crate::theory::averaging::{Side, Theory};
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The paper's four barriers of a three-well U_eff at each grid point, row-major like
/// [`super::Map`]: ΔU1 (well A01 to its right crest), ΔU2 (A03 to the left), ΔU3 (A03 to the
/// right), ΔU4 (A05 to the left). `None` where U_eff does not have three wells (the labels
/// A01, A03, A05 then do not apply) or the parameters are invalid.
#[derive(Debug, Clone)]
pub struct BarrierSurfaces {
    /// The plane.
    pub plane: Plane,
    /// [ΔU1, ΔU2, ΔU3, ΔU4] per grid point.
    pub heights: Vec<[Option<f64>; 4]>,
    /// Number of wells of U_eff per grid point.
    pub wells: Vec<u8>,
}

/// ΔU1..ΔU4 from a theory (see [`BarrierSurfaces`]); also the number of wells.
pub fn paper_barriers(th: &Theory) -> ([Option<f64>; 4], usize) {
    let b = th.barriers();
    let mut wells: Vec<f64> = b.iter().map(|b| b.well).collect();
    wells.dedup();
    let mut out = [None; 4];
    if wells.len() == 3 {
        let find = |w: f64, side: Side| {
            b.iter()
                .find(|x| x.well == w && x.side == side)
                .map(|x| x.height)
        };
        out = [
            find(wells[0], Side::Right),
            find(wells[1], Side::Left),
            find(wells[1], Side::Right),
            find(wells[2], Side::Left),
        ];
    }
    (out, wells.len())
}

/// Barriers on every grid point of the plane, in parallel; `progress(rows_done, rows)`.
pub fn barrier_surfaces(
    plane: &Plane,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> BarrierSurfaces {
    let (nx, ny) = (plane.x.count, plane.y.count);
    let done = AtomicUsize::new(0);
    let rows: Vec<Vec<([Option<f64>; 4], u8)>> = (0..ny)
        .into_par_iter()
        .map(|iy| {
            let row = (0..nx)
                .map(|ix| {
                    let Ok(p) = plane.params(plane.x.value(ix), plane.y.value(iy)) else {
                        return ([None; 4], 0);
                    };
                    match Theory::new(&p, plane.variant) {
                        Ok(th) => {
                            let (h, n) = paper_barriers(&th);
                            (h, n as u8)
                        }
                        Err(_) => ([None; 4], 0),
                    }
                })
                .collect();
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, ny);
            row
        })
        .collect();
    let flat: Vec<_> = rows.into_iter().flatten().collect();
    BarrierSurfaces {
        plane: plane.clone(),
        heights: flat.iter().map(|r| r.0).collect(),
        wells: flat.iter().map(|r| r.1).collect(),
    }
}
