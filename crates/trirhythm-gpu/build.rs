//! Builds the kernel's source as plain C (the CPU emulation of `src/emulate.rs`): the same
//! files that NVRTC compiles for the GPU, with fused multiply–add contraction and fast maths off
//! so that every operation is the correctly rounded IEEE double one, as in the Rust engine.

fn main() {
    println!("cargo:rerun-if-changed=kernel");
    for entry in std::fs::read_dir("kernel").expect("the kernel folder") {
        let path = entry.expect("a kernel file").path();
        println!("cargo:rerun-if-changed={}", path.display());
    }
    cc::Build::new()
        .file("kernel/emulate.c")
        .file("kernel/emulate_paths.c")
        .include("kernel")
        .flag("-std=c99")
        .flag("-ffp-contract=off")
        .flag("-fno-fast-math")
        .opt_level(2)
        .compile("trirhythm_gpu_emulate");
}
