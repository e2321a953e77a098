//! The kernel compiled to PTX by NVRTC (no GPU or driver needed), the options that keep its
//! arithmetic the CPU's, the refusal without a driver, and a launch where a GPU is present.
//!
//! NVRTC is found by the loader (`LD_LIBRARY_PATH`; CI installs the pip wheel
//! `nvidia-cuda-nvrtc-cu12`, `.ci/run`). Where it cannot be loaded the compile checks print the
//! reason and pass, unless `TRIRHYTHM_REQUIRE_NVRTC=1` (set by CI) makes that a failure; the
//! launch check does the same without a GPU unless `TRIRHYTHM_REQUIRE_GPU=1`.
#![cfg(feature = "cuda")]

use trirhythm::Error;
use trirhythm_gpu::cuda::{self, Gpu, Grid};

/// Whether an environment switch is on.
fn required(var: &str) -> bool {
    std::env::var(var).is_ok_and(|v| v == "1")
}

/// `compile_ptx`'s result, or `None` (skip, reason printed) where NVRTC cannot be loaded.
fn compiled(source: &str, defines: &[(&str, String)]) -> Option<trirhythm::Result<String>> {
    match cuda::compile_ptx(source, defines) {
        Err(e @ Error::NotApplicable { .. }) => {
            assert!(
                !required("TRIRHYTHM_REQUIRE_NVRTC"),
                "TRIRHYTHM_REQUIRE_NVRTC=1 but {e}"
            );
            eprintln!("skipped: {e}");
            None
        }
        r => Some(r),
    }
}

/// The names of the `extern "C" __global__` functions of a CUDA source.
fn entries(source: &str) -> Vec<String> {
    source
        .split("extern \"C\" __global__ void ")
        .skip(1)
        .map(|rest| rest.split('(').next().unwrap_or("").trim().to_string())
        .collect()
}

#[test]
fn every_header_of_the_kernel_folder_is_given_to_nvrtc() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("kernel");
    let mut on_disk: Vec<(String, String)> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "h"))
        .map(|p| {
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                std::fs::read_to_string(&p).unwrap(),
            )
        })
        .collect();
    on_disk.sort();
    let mut given: Vec<(String, String)> = cuda::HEADERS
        .iter()
        .map(|(n, t)| (n.to_string(), t.to_string()))
        .collect();
    given.sort();
    let names = |v: &[(String, String)]| v.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    assert_eq!(
        names(&given),
        names(&on_disk),
        "cuda::HEADERS against kernel/*.h"
    );
    assert_eq!(given, on_disk);
}

#[test]
fn the_kernels_compile_to_ptx_naming_their_entries() {
    for (file, source) in [
        ("ensemble.cu", cuda::ENSEMBLE_SOURCE),
        ("probe.cu", cuda::PROBE_SOURCE),
    ] {
        let names = entries(source);
        assert!(
            !names.is_empty(),
            "{file}: no extern \"C\" __global__ entry"
        );
        let Some(ptx) = compiled(source, &[]) else {
            return;
        };
        let ptx = ptx.unwrap_or_else(|e| panic!("{file}: {e}"));
        let (major, minor) = cuda::PTX_ARCH;
        assert!(
            ptx.contains(&format!(".target sm_{major}{minor}")),
            "{file}: PTX for another architecture"
        );
        for n in names {
            assert!(
                ptx.contains(&format!(".entry {n}(")),
                "{file}: the PTX has no entry {n}"
            );
        }
    }
    if let Ok((major, minor)) = cuda::nvrtc_version() {
        eprintln!("NVRTC {major}.{minor}");
    }
}

/// A product and a sum stay two correctly rounded operations: no `fma` in the PTX
/// (`--fmad=false`; NVRTC's default, `--fmad=true`, contracts `a * b + c` to `fma.rn.f64`).
#[test]
fn no_fused_multiply_add_is_contracted() {
    let source = "extern \"C\" __global__ void axpy(double *a) { a[0] = a[1] * a[2] + a[3]; }";
    let Some(ptx) = compiled(source, &[]) else {
        return;
    };
    let ptx = ptx.unwrap();
    assert!(!ptx.contains("fma."), "a fused multiply-add:\n{ptx}");
    assert!(ptx.contains("mul.rn.f64") && ptx.contains("add.rn.f64"));
}

/// The ensemble kernel's own arithmetic has no contracted multiply–add either: compiled with
/// CUDA's transcendental functions left out (`TR_ARITHMETIC_ONLY`; their implementations use
/// `fma` by design), at Fig. 13(a)'s sizes, its PTX holds no `fma` and does hold the kernel's
/// products and sums; in each build `src/gpu.rs` makes (the paper's step, the General kernel's
/// with and without the multiplicative noise's stream) and the emulation's (both steps).
#[test]
fn the_ensemble_kernels_own_arithmetic_is_not_contracted() {
    // (TR_GENERAL, TR_MULTIPLICATIVE, TR_MAX_FRACTIONAL): the emulation's build, then the
    // GPU's for the paper's family, a General plan without η_m or fractional terms, and one
    // with both
    let builds: [&[(&str, &str)]; 4] = [
        &[],
        &[("TR_GENERAL", "0")],
        &[
            ("TR_GENERAL", "1"),
            ("TR_MULTIPLICATIVE", "0"),
            ("TR_MAX_FRACTIONAL", "0"),
        ],
        &[
            ("TR_GENERAL", "1"),
            ("TR_MULTIPLICATIVE", "1"),
            ("TR_MAX_FRACTIONAL", "2"),
        ],
    ];
    for build in builds {
        let mut defines = vec![
            ("TR_ARITHMETIC_ONLY", "1".to_string()),
            ("TR_MAX_CAP", "7".to_string()),
            ("TR_MAX_MODES", "40".to_string()),
        ];
        defines.extend(build.iter().map(|&(k, v)| (k, v.to_string())));
        let Some(ptx) = compiled(cuda::ENSEMBLE_SOURCE, &defines) else {
            return;
        };
        let ptx = ptx.unwrap();
        assert!(
            !ptx.contains("fma."),
            "a fused multiply-add in the kernel's arithmetic ({defines:?})"
        );
        assert!(ptx.contains("mul.rn.f64") && ptx.contains("div.rn.f64"));
    }
}

#[test]
fn defines_reach_the_source_and_a_failure_carries_nvrtc_s_log() {
    let source = "#include \"common.h\"\n#if TR_PROBE_VALUE != 7\n#error TR_PROBE_VALUE is not 7\n\
                  #endif\nextern \"C\" __global__ void k(tr_u64 *b) { b[0] = TR_PROBE_VALUE; }";
    let Some(ok) = compiled(source, &[("TR_PROBE_VALUE", "7".into())]) else {
        return;
    };
    assert!(ok.unwrap().contains(".entry k("));
    let e = cuda::compile_ptx(source, &[("TR_PROBE_VALUE", "8".into())]).unwrap_err();
    let text = e.to_string();
    assert!(
        text.contains("TR_PROBE_VALUE is not 7") && text.contains("-DTR_PROBE_VALUE=8"),
        "{text}"
    );
    let e = cuda::compile_ptx(source, &[("7UP", "1".into())]).unwrap_err();
    assert!(e.to_string().contains("`7UP` is not a C identifier"), "{e}");
}

/// `device()` never panics: the device's description where a driver and a GPU are, otherwise
/// the refusal naming the GPU backend and what failed.
#[test]
fn device_is_described_or_refused_with_the_reason() {
    match cuda::device() {
        Ok(info) => {
            eprintln!("device: {info}");
            assert!(!info.name.is_empty() && info.devices >= 1);
            assert!(info.compute_capability.0 >= 3 && info.multiprocessors > 0);
            assert!(info.memory_bytes > 1 << 28);
        }
        Err(Error::NotApplicable {
            method,
            assumption,
            reason,
        }) => {
            assert!(!required("TRIRHYTHM_REQUIRE_GPU"), "no GPU: {reason}");
            assert_eq!(method, "the GPU backend");
            assert_eq!(assumption, "a CUDA driver and device");
            assert!(
                reason.contains("libcuda") || reason.contains("the driver is loaded but"),
                "{reason}"
            );
            eprintln!("no device: {reason}");
        }
        Err(e) => panic!("neither a device nor the refusal: {e:?}"),
    }
}

/// On a GPU: the probe kernel copies 1000 doubles' bits plus an offset, through the launch
/// helper, with a grid of partly used blocks; an unknown entry is `Error::Unknown`.
#[test]
fn a_launch_moves_the_bits_on_a_device() {
    let gpu = match Gpu::open() {
        Ok(g) => g,
        Err(e) => {
            assert!(!required("TRIRHYTHM_REQUIRE_GPU"), "no GPU: {e}");
            eprintln!("skipped: {e}");
            return;
        }
    };
    let ptx = cuda::compile_ptx_for(cuda::PROBE_SOURCE, &[], gpu.info().compute_capability)
        .expect("the probe kernel compiles for the device");
    let module = gpu.load(&ptx).unwrap();
    let kernel = module.kernel("tr_probe").unwrap();
    let x: Vec<f64> = (0..1000).map(|i| (i as f64).sqrt() - 7.25).collect();
    let input = gpu.upload(&x).unwrap();
    let mut bits = gpu.zeros::<u64>(x.len()).unwrap();
    let (n, offset) = (x.len() as u64, 3u64);
    gpu.launch(&kernel, Grid::cover(x.len(), 128).unwrap(), |a| {
        use cuda::PushKernelArg;
        a.arg(&input).arg(&mut bits).arg(&n).arg(&offset);
    })
    .unwrap();
    let got = gpu.download(&bits).unwrap();
    let want: Vec<u64> = x.iter().map(|v| v.to_bits() + offset).collect();
    assert_eq!(got, want);
    assert!(matches!(
        module.kernel("tr_no_such_kernel"),
        Err(Error::Unknown { .. })
    ));
}
