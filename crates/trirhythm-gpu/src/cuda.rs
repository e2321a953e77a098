//! The CUDA host side: the driver and NVRTC loaded at run time, the kernel compiled to PTX, a
//! module loaded and a kernel launched.
//!
//! **Loading.** Nothing CUDA is needed to build: `cudarc` opens `libcuda` (the driver) and
//! `libnvrtc` (the run-time compiler) with `dlopen` on first use, trying the names of
//! [`library_names`] (`libnvrtc.so`, `libnvrtc.so.12`, …, found through the loader's search
//! path, `LD_LIBRARY_PATH` included). cudarc panics when none loads, or when one loads without
//! a symbol it binds; here [`device`] and [`compile_ptx`] first probe the same names with
//! `libloading` and return [`Error::NotApplicable`] naming what failed, and they call cudarc's
//! loader inside [`std::panic::catch_unwind`] for the case the probe cannot see (a library too
//! old for the bindings). A machine without a GPU gets an error, never a panic.
//!
//! **Compiling.** [`compile_ptx`] hands NVRTC the kernel's source with the headers of
//! `kernel/` ([`HEADERS`], their text built into the library, so nothing on disk is read at run
//! time) and the options `--std=c++14 -default-device --fmad=false --prec-div=true
//! --prec-sqrt=true --ftz=false`: no fused multiply–add contraction and IEEE division and
//! square root, so every `+ − × ÷ √` is the correctly rounded double operation, as in the CPU
//! engine and in the C build of the emulation (`kernel/common.h`). The PTX targets the virtual
//! architecture [`PTX_ARCH`] unless the caller names the device's ([`compile_ptx_for`]); the
//! driver compiles it for the device when the module is loaded. A failed compilation's error
//! holds NVRTC's log.
//!
//! **Launching.** [`Gpu`] holds the context and stream of device 0: [`Gpu::upload`],
//! [`Gpu::zeros`] and [`Gpu::download`] move buffers, [`Gpu::load`] loads a PTX module,
//! [`Module::kernel`] finds an entry point, and [`Gpu::launch`] launches it on a [`Grid`] with
//! the arguments a closure pushes (cudarc's typed `LaunchArgs::arg`: a scalar or a buffer), then
//! waits for it.
//!
//! Reference: the CUDA driver API and NVRTC user guides (NVIDIA, CUDA 12); cudarc 0.16's
//! `driver` and `nvrtc` modules.
//!
//! Tests: `tests/ptx.rs` (the kernel compiled to PTX wherever NVRTC can be loaded, no GPU
//! needed; [`device`]'s error without a driver; a launch where a GPU is present) and this
//! module's unit tests (the probe's error names every library name it tried).

use cudarc::driver::DriverError;
use std::ffi::{c_char, CString};
use trirhythm::{Error, Result};

mod launch;
// what a caller of [`Gpu::launch`] names: the buffers and the argument pusher
pub use cudarc::driver::{CudaSlice, LaunchArgs, PushKernelArg};
pub use launch::{Gpu, Grid, Kernel, Module};

/// The kernel's headers as NVRTC sees them: `#include "NAME"` in the source finds NAME here.
/// Every header of `kernel/` belongs in this list (`tests/ptx.rs` checks it).
pub const HEADERS: &[(&str, &str)] = &[
    ("common.h", include_str!("../kernel/common.h")),
    ("noise.h", include_str!("../kernel/noise.h")),
    ("plan.h", include_str!("../kernel/plan.h")),
    ("memory.h", include_str!("../kernel/memory.h")),
    ("step.h", include_str!("../kernel/step.h")),
    ("general.h", include_str!("../kernel/general.h")),
    ("record.h", include_str!("../kernel/record.h")),
    ("path.h", include_str!("../kernel/path.h")),
];

/// The ensemble kernel's source, `kernel/ensemble.cu`.
pub const ENSEMBLE_SOURCE: &str = include_str!("../kernel/ensemble.cu");

/// The host side's probe kernel, `kernel/probe.cu`: `tr_probe(x, bits, n, offset)` writes
/// `bits[i] = to_bits(x[i]) + offset` for `i < n` (a launch checked without arithmetic).
pub const PROBE_SOURCE: &str = include_str!("../kernel/probe.cu");

/// The virtual architecture [`compile_ptx`] targets: compute capability 7.5 (Turing and later:
/// the oldest that both NVRTC 12 and NVRTC 13, which dropped Volta, compile for). The driver
/// compiles the PTX for the device's own architecture when the module is loaded; the ensemble
/// kernel is compiled for the device's own ([`compile_ptx_for`]).
pub const PTX_ARCH: (u32, u32) = (7, 5);

/// The CUDA version of cudarc's bindings (its `cuda-12060` feature): the version numbers in
/// the library names it tries.
const CUDA_VERSION: (u32, u32) = (12, 6);

/// The method and assumption of every refusal of this module.
fn refuse(assumption: &str, reason: String) -> Error {
    Error::NotApplicable {
        method: "the GPU backend".into(),
        assumption: assumption.into(),
        reason,
    }
}

/// A driver call's failure as an error naming the call.
fn driver_error(call: &str, e: DriverError) -> Error {
    let name = e
        .error_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|_| format!("{e:?}"));
    let text = e
        .error_string()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    Error::Undefined {
        what: "the GPU run",
        why: format!("{call} failed: {name} ({text})"),
    }
}

/// The file names under which the loader is asked for the shared library `lib` (`cuda`,
/// `nvrtc`), in the order cudarc tries them: the plain name, the names with the pointer width
/// and the CUDA version (Windows), and the versioned sonames (`libnvrtc.so.12`, …).
pub fn library_names(lib: &str) -> Vec<String> {
    use std::env::consts::{DLL_PREFIX as P, DLL_SUFFIX as S};
    let (major, minor) = CUDA_VERSION;
    let w = if cfg!(target_pointer_width = "32") {
        "32"
    } else {
        "64"
    };
    vec![
        format!("{P}{lib}{S}"),
        format!("{P}{lib}{w}{S}"),
        format!("{P}{lib}{w}_{major}{S}"),
        format!("{P}{lib}{w}_{major}{minor}{S}"),
        format!("{P}{lib}{w}_{major}{minor}_0{S}"),
        format!("{P}{lib}{w}_{major}0_{minor}{S}"),
        format!("{P}{lib}{w}_10{S}"),
        format!("{P}{lib}{w}_{major}0_0{S}"),
        format!("{P}{lib}{w}_9{S}"),
        format!("{P}{lib}{S}.{major}"),
        format!("{P}{lib}{S}.11"),
        format!("{P}{lib}{S}.10"),
        format!("{P}{lib}{S}.1"),
    ]
}

/// Whether one of `names` loads (the first that does), or the refusal naming them all and the
/// loader's last message.
fn probe(what: &str, names: &[String], assumption: &str) -> Result<String> {
    let mut last = String::new();
    for n in names {
        // SAFETY: loading runs the library's initialisers; the CUDA libraries' are sound to
        // run (cudarc loads the same files), and the handle is closed again at once
        match unsafe { libloading::Library::new(n) } {
            Ok(_) => return Ok(n.clone()),
            Err(e) => last = e.to_string(),
        }
    }
    Err(refuse(
        assumption,
        format!(
            "{what} could not be loaded: none of {} is on the loader's search path (add its \
             directory to LD_LIBRARY_PATH); the last attempt said: {last}",
            names.join(", ")
        ),
    ))
}

/// Run cudarc's loader (`f` touches its library), turning its panic into the refusal.
fn guarded<T>(what: &str, assumption: &str, f: impl FnOnce() -> T) -> Result<T> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).map_err(|payload| {
        let message = payload
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_else(|| "no message".into());
        refuse(
            assumption,
            format!("{what} was found but could not be bound: {message}"),
        )
    })
}

const DRIVER: &str = "a CUDA driver and device";
const COMPILER: &str =
    "NVRTC, CUDA's run-time compiler (libnvrtc, e.g. from the pip wheel nvidia-cuda-nvrtc-cu12)";

/// The driver library, loaded and bound (once; later calls only check).
fn load_driver() -> Result<()> {
    let found = probe("the CUDA driver (libcuda)", &library_names("cuda"), DRIVER)?;
    guarded(&found, DRIVER, || {
        // SAFETY: only loads and binds the library (cudarc's loader)
        unsafe { cudarc::driver::sys::culib() };
    })
}

/// NVRTC, loaded and bound.
fn load_nvrtc() -> Result<()> {
    let found = probe("NVRTC (libnvrtc)", &library_names("nvrtc"), COMPILER)?;
    guarded(&found, COMPILER, || {
        // SAFETY: only loads and binds the library (cudarc's loader)
        unsafe { cudarc::nvrtc::sys::culib() };
    })
}

/// What [`device`] reports of the GPU the backend uses (device 0).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DeviceInfo {
    /// The device's name (`NVIDIA H100 80GB HBM3`).
    pub name: String,
    /// Its compute capability (major, minor): (9, 0) for Hopper.
    pub compute_capability: (u32, u32),
    /// Its streaming multiprocessors.
    pub multiprocessors: u32,
    /// Its global memory in bytes.
    pub memory_bytes: u64,
    /// The driver's CUDA version (major, minor).
    pub driver_version: (u32, u32),
    /// How many CUDA devices the driver sees.
    pub devices: u32,
}

impl std::fmt::Display for DeviceInfo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} (compute capability {}.{}, {} multiprocessors, {:.1} GiB; CUDA driver {}.{})",
            self.name,
            self.compute_capability.0,
            self.compute_capability.1,
            self.multiprocessors,
            self.memory_bytes as f64 / (1u64 << 30) as f64,
            self.driver_version.0,
            self.driver_version.1
        )
    }
}

/// The GPU the backend would use (device 0): the driver loaded and initialised, the device's
/// name, compute capability, multiprocessors and memory. Without a loadable driver, or with no
/// device, [`Error::NotApplicable`] saying what failed.
pub fn device() -> Result<DeviceInfo> {
    use cudarc::driver::result;
    use cudarc::driver::sys::CUdevice_attribute as A;
    load_driver()?;
    let no_device = |call: &str, e: DriverError| match driver_error(call, e) {
        Error::Undefined { why, .. } => refuse(DRIVER, format!("the driver is loaded but {why}")),
        other => other,
    };
    result::init().map_err(|e| no_device("cuInit", e))?;
    let devices = result::device::get_count().map_err(|e| no_device("cuDeviceGetCount", e))?;
    if devices < 1 {
        return Err(refuse(
            DRIVER,
            "the driver is loaded but sees no CUDA device".into(),
        ));
    }
    let dev = result::device::get(0).map_err(|e| driver_error("cuDeviceGet", e))?;
    let attribute = |a: A| -> Result<u32> {
        // SAFETY: `dev` is a valid device handle of the initialised driver
        let v = unsafe { result::device::get_attribute(dev, a) }
            .map_err(|e| driver_error("cuDeviceGetAttribute", e))?;
        Ok(v.max(0) as u32)
    };
    let mut version: std::ffi::c_int = 0;
    // SAFETY: writes one int
    unsafe { cudarc::driver::sys::cuDriverGetVersion(&mut version) }
        .result()
        .map_err(|e| driver_error("cuDriverGetVersion", e))?;
    Ok(DeviceInfo {
        name: result::device::get_name(dev).map_err(|e| driver_error("cuDeviceGetName", e))?,
        compute_capability: (
            attribute(A::CU_DEVICE_ATTRIBUTE_COMPUTE_CAPABILITY_MAJOR)?,
            attribute(A::CU_DEVICE_ATTRIBUTE_COMPUTE_CAPABILITY_MINOR)?,
        ),
        multiprocessors: attribute(A::CU_DEVICE_ATTRIBUTE_MULTIPROCESSOR_COUNT)?,
        // SAFETY: `dev` is a valid device handle
        memory_bytes: unsafe { result::device::total_mem(dev) }
            .map_err(|e| driver_error("cuDeviceTotalMem", e))? as u64,
        driver_version: (
            version.max(0) as u32 / 1000,
            (version.max(0) as u32 % 1000) / 10,
        ),
        devices: devices as u32,
    })
}

/// NVRTC's version (major, minor), loading it first.
pub fn nvrtc_version() -> Result<(u32, u32)> {
    load_nvrtc()?;
    let (mut major, mut minor) = (0, 0);
    // SAFETY: writes two ints
    unsafe { cudarc::nvrtc::sys::nvrtcVersion(&mut major, &mut minor) }
        .result()
        .map_err(|e| nvrtc_failed("nvrtcVersion", e))?;
    Ok((major.max(0) as u32, minor.max(0) as u32))
}

fn nvrtc_failed(call: &str, e: cudarc::nvrtc::result::NvrtcError) -> Error {
    Error::Undefined {
        what: "the GPU kernel's compilation",
        why: format!("{call} failed: {:?}", e.0),
    }
}

/// `source` (CUDA C++, e.g. `kernel/ensemble.cu`) compiled to PTX for [`PTX_ARCH`] with the
/// kernel's [`HEADERS`] and the macros `defines` (`-DNAME=VALUE`); see the module docs for the
/// options. Without a loadable NVRTC, [`Error::NotApplicable`]; a failed compilation's error
/// holds NVRTC's log.
pub fn compile_ptx(source: &str, defines: &[(&str, String)]) -> Result<String> {
    compile_ptx_for(source, defines, PTX_ARCH)
}

/// [`compile_ptx`] for the virtual architecture `compute_{arch.0}{arch.1}` (a device's compute
/// capability: [`DeviceInfo::compute_capability`]).
pub fn compile_ptx_for(
    source: &str,
    defines: &[(&str, String)],
    arch: (u32, u32),
) -> Result<String> {
    use cudarc::nvrtc::{result, sys};
    let text = |what: &str, s: &str| {
        CString::new(s).map_err(|_| Error::Undefined {
            what: "the GPU kernel's compilation",
            why: format!("{what} holds a NUL byte"),
        })
    };
    let mut options = vec![
        format!("--gpu-architecture=compute_{}{}", arch.0, arch.1),
        "--std=c++14".to_string(),
        "-default-device".to_string(),
        "--fmad=false".to_string(),
        "--prec-div=true".to_string(),
        "--prec-sqrt=true".to_string(),
        "--ftz=false".to_string(),
    ];
    for (name, value) in defines {
        let valid = !name.is_empty()
            && !name.starts_with(|c: char| c.is_ascii_digit())
            && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
        if !valid {
            return Err(Error::Undefined {
                what: "the GPU kernel's compilation",
                why: format!("the macro name `{name}` is not a C identifier"),
            });
        }
        options.push(format!("-D{name}={value}"));
    }
    let src = text("the source", source)?;
    let name = text("the program name", "ensemble.cu")?;
    let header_text: Vec<CString> = HEADERS
        .iter()
        .map(|(n, t)| text(n, t))
        .collect::<Result<_>>()?;
    let header_name: Vec<CString> = HEADERS
        .iter()
        .map(|(n, _)| text("a header's name", n))
        .collect::<Result<_>>()?;
    let text_ptrs: Vec<*const c_char> = header_text.iter().map(|s| s.as_ptr()).collect();
    let name_ptrs: Vec<*const c_char> = header_name.iter().map(|s| s.as_ptr()).collect();
    load_nvrtc()?;
    let mut prog: sys::nvrtcProgram = std::ptr::null_mut();
    // SAFETY: every pointer is to a NUL-terminated string alive until the program is destroyed
    // below; the arrays hold `HEADERS.len()` entries each
    unsafe {
        sys::nvrtcCreateProgram(
            &mut prog,
            src.as_ptr(),
            name.as_ptr(),
            HEADERS.len() as std::ffi::c_int,
            text_ptrs.as_ptr(),
            name_ptrs.as_ptr(),
        )
    }
    .result()
    .map_err(|e| nvrtc_failed("nvrtcCreateProgram", e))?;
    // SAFETY: `prog` was created above and is destroyed once, after its last use
    let outcome = unsafe {
        match result::compile_program(prog, &options) {
            Ok(()) => result::get_ptx(prog).map_err(|e| nvrtc_failed("nvrtcGetPTX", e)),
            Err(e) => {
                let log = result::get_program_log(prog)
                    .map(|l| chars_to_string(&l))
                    .unwrap_or_else(|_| "(no log)".into());
                Err(Error::Undefined {
                    what: "the GPU kernel's compilation",
                    why: format!(
                        "NVRTC failed ({:?}) with the options {}:\n{}",
                        e.0,
                        options.join(" "),
                        log.trim_end()
                    ),
                })
            }
        }
    };
    // SAFETY: destroyed once
    let _ = unsafe { result::destroy_program(prog) };
    Ok(chars_to_string(&outcome?))
}

/// A NUL-terminated `char` buffer as text.
fn chars_to_string(buf: &[c_char]) -> String {
    let bytes: Vec<u8> = buf
        .iter()
        .map(|&c| c as u8)
        .take_while(|&b| b != 0)
        .collect();
    String::from_utf8_lossy(&bytes).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_library_is_refused_naming_every_name_tried() {
        let names = library_names("trirhythm_no_such_library");
        let e = probe("the test library", &names, DRIVER).unwrap_err();
        let Error::NotApplicable {
            method,
            assumption,
            reason,
        } = &e
        else {
            panic!("not a refusal: {e:?}");
        };
        assert_eq!(method, "the GPU backend");
        assert_eq!(assumption, DRIVER);
        for n in &names {
            assert!(reason.contains(n.as_str()), "{n} missing from: {reason}");
        }
        assert!(reason.starts_with("the test library could not be loaded"));
    }

    #[test]
    fn library_names_include_the_versioned_soname() {
        let names = library_names("nvrtc");
        if cfg!(target_os = "linux") {
            assert_eq!(names[0], "libnvrtc.so");
            assert!(names.contains(&"libnvrtc.so.12".to_string()));
            assert!(library_names("cuda").contains(&"libcuda.so.1".to_string()));
        }
        assert_eq!(names.len(), 13);
    }

    #[test]
    fn a_panic_of_the_loader_becomes_the_refusal() {
        let e = guarded::<()>("libfake.so", COMPILER, || {
            std::panic::panic_any("symbol nvrtcFoo missing".to_string())
        })
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            format!(
                "the GPU backend does not apply to this model: it assumes {COMPILER}; \
                 libfake.so was found but could not be bound: symbol nvrtcFoo missing"
            )
        );
    }
}
