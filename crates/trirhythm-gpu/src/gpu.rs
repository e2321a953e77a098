//! The GPU backend of ensembles: `kernel/ensemble.cu` (one thread per path: the engine's step
//! and recorder, `kernel/path.h`) compiled by NVRTC for the device with the plan's window and
//! modes as compile-time sizes (the largest of the leading memory's and the fractional terms'
//! memories') and the General kernel's parts the problem uses (`TR_GENERAL`,
//! `TR_MULTIPLICATIVE`, `TR_MAX_FRACTIONAL`: `kernel/general.h`), its `GeneralPlan` uploaded
//! beside the step's plan, launched over the paths in chunks that bound the device memory,
//! each path's statistics copied back and converted into the engine's [`PathStats`]
//! ([`crate::paths`]), then merged by the engine's `merge`, as on the CPU.
//!
//! Progress: the monitor hears the steps of every finished chunk and may stop the run between
//! chunks ([`trirhythm::Error::Cancelled`]); each path's statistics are handed to it as they
//! come back.
//!
//! Tests: `tests/gpu.rs` (where a GPU is present: the kernel's statistics against the CPU
//! engine's, and the throughput), `tests/emulation.rs` (the same source compiled as C, bit for
//! bit against the engine, everywhere).

use crate::cuda::{compile_ptx_for, CudaSlice, Gpu, Grid, PushKernelArg};
use crate::paths::{first_error, Batch, Passage, PathEnd, Prepared, Raw};
use cudarc::driver::{DeviceRepr, ValidAsZeroBits};
use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};
use std::time::Instant;
use trirhythm::analysis::ensemble::{EnsembleSpec, PathStats};
use trirhythm::engine::{PredictorCorrector, Problem};
use trirhythm::monitor::Monitor;
use trirhythm::Result;

// SAFETY: plain `#[repr(C)]` structures of integers and doubles (the kernel's layouts), for
// which all-zero bits are valid values
unsafe impl DeviceRepr for Batch {}
unsafe impl ValidAsZeroBits for Batch {}
unsafe impl DeviceRepr for Passage {}
unsafe impl ValidAsZeroBits for Passage {}
unsafe impl DeviceRepr for PathEnd {}
unsafe impl ValidAsZeroBits for PathEnd {}

/// Threads per block.
const THREADS: u32 = 128;
/// Most paths of one launch.
const MAX_CHUNK: usize = 1 << 18;
/// Most bytes of per-path outputs on the device at once.
const CHUNK_BYTES: usize = 1 << 31;

/// The kernel's PTX for these sizes and this architecture, compiled once per process: a map
/// --simulate runs one ensemble per grid point, and NVRTC takes about a second for the kernel,
/// which most points would spend on the same sizes (the driver keeps its own cache of the
/// machine code it makes of a PTX).
fn cached_ptx(defines: &[(&str, String)], arch: (u32, u32)) -> Result<String> {
    type Cache = Mutex<HashMap<(Vec<(String, String)>, (u32, u32)), String>>;
    static CACHE: OnceLock<Cache> = OnceLock::new();
    let key: Vec<(String, String)> = defines
        .iter()
        .map(|(n, v)| (n.to_string(), v.clone()))
        .collect();
    let cache = CACHE.get_or_init(Default::default);
    let held = cache
        .lock()
        .unwrap_or_else(|p| p.into_inner())
        .get(&(key.clone(), arch))
        .cloned();
    if let Some(ptx) = held {
        return Ok(ptx);
    }
    let ptx = compile_ptx_for(crate::cuda::ENSEMBLE_SOURCE, defines, arch)?;
    cache
        .lock()
        .unwrap_or_else(|p| p.into_inner())
        .insert((key, arch), ptx.clone());
    Ok(ptx)
}

/// The bytes of a plain value, to upload a structure of another crate as the kernel reads it.
fn bytes_of<T: Copy>(value: &T) -> Vec<u8> {
    // SAFETY: `T` is a `#[repr(C)]` plain-data structure (StepPlan, GeneralPlan, RecordPlan,
    // TrNoise) without padding that could be uninitialised in a way the kernel reads: its
    // padding bytes are copied but never used as values
    unsafe { std::slice::from_raw_parts(value as *const T as *const u8, std::mem::size_of::<T>()) }
        .to_vec()
}

/// The statistics of every path of an ensemble stepped on the GPU, and where the time went.
#[derive(Debug, Clone)]
pub struct GpuPaths {
    /// Every path's statistics, in path order (the engine's `merge` takes them).
    pub stats: Vec<PathStats>,
    /// The device's name.
    pub device: String,
    /// Seconds of NVRTC's compilation and the module's loading.
    pub compile_seconds: f64,
    /// Seconds in the kernel's launches (to their end).
    pub kernel_seconds: f64,
    /// Seconds from the call to its return.
    pub total_seconds: f64,
}

/// The paths 0..`spec.paths` of the ensemble on the GPU (the run's checks first, then the
/// device), with the time spent compiling, in the kernel and in all.
pub fn gpu_paths(
    problem: &Problem,
    method: &PredictorCorrector,
    spec: &EnsembleSpec,
    monitor: &dyn Monitor<PathStats>,
) -> Result<GpuPaths> {
    let start = Instant::now();
    let prep = Prepared::new(problem, method, spec)?;
    monitor.check()?;
    let gpu = Gpu::open()?;
    let compiling = Instant::now();
    // the per-path arrays sized for the leading memory and the fractional terms' memories
    let g = &prep.general;
    let terms = g.fractional_terms as usize;
    let memories = g.memories[..terms]
        .iter()
        .zip(&g.fractional_memory)
        .filter(|(_, &has)| has != 0)
        .map(|(m, _)| m);
    let cap = memories
        .clone()
        .map(|m| m.cap)
        .fold(prep.plan.cap, u32::max);
    let modes = memories.map(|m| m.modes).fold(prep.plan.modes, u32::max);
    let defines = [
        ("TR_MAX_CAP", cap.max(1).to_string()),
        ("TR_MAX_MODES", modes.max(4).to_string()),
        ("TR_GENERAL", g.active.to_string()),
        ("TR_MULTIPLICATIVE", g.multiplicative.to_string()),
        ("TR_MAX_FRACTIONAL", terms.to_string()),
    ];
    let ptx = cached_ptx(&defines, gpu.info().compute_capability)?;
    let module = gpu.load(&ptx)?;
    let kernel = module.kernel("tr_ensemble")?;
    let compile_seconds = compiling.elapsed().as_secs_f64();
    let mut kernel_seconds = 0.0;
    let (zx, zf) = trirhythm::maths::ziggurat_tables();
    let plan = gpu.upload(&bytes_of(&prep.plan))?;
    let general = gpu.upload(&bytes_of(&prep.general))?;
    let noise = gpu.upload(&bytes_of(&prep.noise))?;
    let record = gpu.upload(&bytes_of(&prep.record))?;
    let zx = gpu.upload(&zx[..])?;
    let zf = gpu.upload(&zf[..])?;
    let starts: Vec<f64> = problem.starts().iter().flat_map(|&(u, v)| [u, v]).collect();
    let nstarts = problem.starts().len() as u64;
    let starts = gpu.upload(&starts)?;
    let (nb, nw) = (prep.record.batches as usize, prep.record.wells as usize);
    let per_path = nb * std::mem::size_of::<Batch>()
        + nb * nw * 8
        + nw * nw * std::mem::size_of::<Passage>()
        + prep.counts * 8
        + std::mem::size_of::<PathEnd>();
    let chunk = (CHUNK_BYTES / per_path).clamp(1, MAX_CHUNK);
    let total = spec.paths as u64 * prep.steps;
    let mut results = Vec::with_capacity(spec.paths);
    let mut first = 0usize;
    while first < spec.paths {
        monitor.check()?;
        let count = chunk.min(spec.paths - first);
        let batches: CudaSlice<Batch> = gpu.zeros(count * nb)?;
        let wells: CudaSlice<u64> = gpu.zeros((count * nb * nw).max(1))?;
        let passages: CudaSlice<Passage> = gpu.zeros((count * nw * nw).max(1))?;
        let counts: CudaSlice<u64> = gpu.zeros(count * prep.counts)?;
        let ends: CudaSlice<PathEnd> = gpu.zeros(count)?;
        let (first64, count64) = (first as u64, count as u64);
        let launched = Instant::now();
        gpu.launch(&kernel, Grid::cover(count, THREADS)?, |a| {
            a.arg(&plan)
                .arg(&general)
                .arg(&noise)
                .arg(&record)
                .arg(&zx)
                .arg(&zf)
                .arg(&prep.seed)
                .arg(&first64)
                .arg(&count64)
                .arg(&prep.steps)
                .arg(&starts)
                .arg(&nstarts)
                .arg(&batches)
                .arg(&wells)
                .arg(&passages)
                .arg(&counts)
                .arg(&ends);
        })?;
        kernel_seconds += launched.elapsed().as_secs_f64();
        let batches = gpu.download(&batches)?;
        let wells = gpu.download(&wells)?;
        let passages = gpu.download(&passages)?;
        let counts = gpu.download(&counts)?;
        let ends = gpu.download(&ends)?;
        for i in 0..count {
            let raw = Raw {
                batches: batches[i * nb..(i + 1) * nb].to_vec(),
                wells: wells[i * nb * nw..(i + 1) * nb * nw].to_vec(),
                passages: passages[i * nw * nw..(i + 1) * nw * nw].to_vec(),
                counts: counts[i * prep.counts..(i + 1) * prep.counts].to_vec(),
                end: ends[i],
            };
            let stats = raw.into_stats(&prep, problem, (first + i) as u64);
            if let Ok(s) = &stats {
                monitor.finished(s)?;
            }
            results.push(stats);
        }
        first += count;
        monitor.progress(first as u64 * prep.steps, total);
    }
    Ok(GpuPaths {
        stats: first_error(results)?,
        device: gpu.info().name.clone(),
        compile_seconds,
        kernel_seconds,
        total_seconds: start.elapsed().as_secs_f64(),
    })
}
