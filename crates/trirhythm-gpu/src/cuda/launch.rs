//! The launch helper: device 0's context and stream ([`Gpu`]), buffers, a PTX module
//! ([`Module`]) and its entry points ([`Kernel`]), launched on a [`Grid`] with typed arguments
//! (see the parent module's docs).
//!
//! Tests: `tests/ptx.rs` (`a_launch_moves_the_bits_on_a_device`, where a GPU is present) and
//! this module's unit test of [`Grid::cover`].

use super::{device, driver_error, DeviceInfo};
use cudarc::driver::{
    CudaContext, CudaFunction, CudaModule, CudaSlice, CudaStream, DeviceRepr, LaunchArgs,
    LaunchConfig, ValidAsZeroBits,
};
use std::sync::Arc;
use trirhythm::{Error, Result};

/// A launch's shape: `blocks` blocks of `threads` threads, `shared_bytes` of dynamic shared
/// memory per block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Grid {
    /// Blocks in the grid (x).
    pub blocks: u32,
    /// Threads per block (x).
    pub threads: u32,
    /// Dynamic shared memory per block, in bytes.
    pub shared_bytes: u32,
}

impl Grid {
    /// One thread per item for `items` items (`paths`), `threads` per block: the fewest blocks
    /// that cover them.
    pub fn cover(items: usize, threads: u32) -> Result<Grid> {
        if !(1..=1024).contains(&threads) {
            return Err(Error::invalid(
                "threads per block",
                threads as f64,
                "1 to 1024",
            ));
        }
        let blocks = items.div_ceil(threads as usize);
        if blocks == 0 || blocks > u32::MAX as usize {
            return Err(Error::invalid(
                "paths",
                items as f64,
                format!("1 to {} in one launch", u32::MAX as u64 * threads as u64),
            ));
        }
        Ok(Grid {
            blocks: blocks as u32,
            threads,
            shared_bytes: 0,
        })
    }
}

/// The GPU of the backend (device 0): its context and stream.
pub struct Gpu {
    context: Arc<CudaContext>,
    stream: Arc<CudaStream>,
    info: DeviceInfo,
}

/// A PTX module loaded on the [`Gpu`].
pub struct Module(Arc<CudaModule>);

/// A kernel's entry point in a [`Module`].
pub struct Kernel {
    function: CudaFunction,
    name: String,
}

impl Gpu {
    /// Open device 0 (the refusal of [`device`] where there is none).
    pub fn open() -> Result<Gpu> {
        let info = device()?;
        let context = CudaContext::new(0).map_err(|e| driver_error("cuCtxCreate", e))?;
        let stream = context.default_stream();
        Ok(Gpu {
            context,
            stream,
            info,
        })
    }

    /// What the device is.
    pub fn info(&self) -> &DeviceInfo {
        &self.info
    }

    /// Load a PTX module (the driver compiles it for the device).
    pub fn load(&self, ptx: &str) -> Result<Module> {
        self.context
            .load_module(cudarc::nvrtc::Ptx::from_src(ptx))
            .map(Module)
            .map_err(|e| driver_error("cuModuleLoadData", e))
    }

    /// A device buffer holding `host`.
    pub fn upload<T: DeviceRepr>(&self, host: &[T]) -> Result<CudaSlice<T>> {
        self.stream
            .memcpy_stod(host)
            .map_err(|e| driver_error("cuMemcpyHtoD", e))
    }

    /// A device buffer of `len` zeros.
    pub fn zeros<T: DeviceRepr + ValidAsZeroBits>(&self, len: usize) -> Result<CudaSlice<T>> {
        self.stream
            .alloc_zeros(len)
            .map_err(|e| driver_error("cuMemAlloc", e))
    }

    /// A device buffer's contents (after the work queued before it).
    pub fn download<T: DeviceRepr>(&self, device: &CudaSlice<T>) -> Result<Vec<T>> {
        self.stream
            .memcpy_dtov(device)
            .map_err(|e| driver_error("cuMemcpyDtoH", e))
    }

    /// Launch `kernel` on `grid` with the arguments `args` pushes, in the order of the kernel's
    /// parameters (`a.arg(&buffer).arg(&n)`: a `&CudaSlice<T>` for a `T*`, a `&T` for a
    /// scalar), and wait for it to finish. The argument list must match the kernel's
    /// signature: the driver cannot check it.
    pub fn launch<'a>(
        &'a self,
        kernel: &'a Kernel,
        grid: Grid,
        args: impl FnOnce(&mut LaunchArgs<'a>),
    ) -> Result<()> {
        let mut builder = self.stream.launch_builder(&kernel.function);
        args(&mut builder);
        let config = LaunchConfig {
            grid_dim: (grid.blocks, 1, 1),
            block_dim: (grid.threads, 1, 1),
            shared_mem_bytes: grid.shared_bytes,
        };
        // SAFETY: the caller's arguments are typed (cudarc's `PushKernelArg`) and borrowed for
        // the launch; their number and order are the caller's contract with the kernel
        unsafe { builder.launch(config) }
            .map_err(|e| driver_error(&format!("launching `{}`", kernel.name), e))?;
        self.stream
            .synchronize()
            .map_err(|e| driver_error(&format!("running `{}`", kernel.name), e))
    }
}

impl Module {
    /// The entry point `name` (an `extern "C" __global__` function of the source).
    pub fn kernel(&self, name: &str) -> Result<Kernel> {
        let function = self.0.load_function(name).map_err(|e| match e {
            e if e.0 == cudarc::driver::sys::CUresult::CUDA_ERROR_NOT_FOUND => Error::Unknown {
                kind: "GPU kernel",
                name: name.into(),
                expected: "an extern \"C\" __global__ function of the module".into(),
            },
            e => driver_error("cuModuleGetFunction", e),
        })?;
        Ok(Kernel {
            function,
            name: name.into(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grid_covers_every_path_with_the_fewest_blocks() {
        assert_eq!(
            Grid::cover(1000, 256).unwrap(),
            Grid {
                blocks: 4,
                threads: 256,
                shared_bytes: 0
            }
        );
        assert_eq!(Grid::cover(1024, 256).unwrap().blocks, 4);
        assert_eq!(Grid::cover(1025, 256).unwrap().blocks, 5);
        assert!(matches!(
            Grid::cover(10, 0),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(matches!(
            Grid::cover(0, 128),
            Err(Error::InvalidParameter { .. })
        ));
    }
}
