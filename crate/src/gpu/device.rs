//! The GPU side: one wgpu device and the compiled kernel, and one dispatch per map.
//!
//! Natively wgpu picks Vulkan, Metal or DX12 (lavapipe, Mesa's CPU Vulkan driver, on a
//! machine without a GPU); in the page it is the browser's WebGPU. No adapter is not an
//! error: [`GpuMapper::request`] returns `Ok(None)` and the caller uses the CPU path.
//! Device errors (validation, out of memory, a lost device) come back as
//! [`RideError::Gpu`], never as a panic: the uncaptured-error handler only records them.

use super::cell::{offset, HALF_STRIDE};
use super::quadrature::NODES_PER_PANEL;
use super::MapInput;
use crate::error::{Result, RideError};
use crate::evaluate::Criteria;
use std::future::Future;
use std::pin::Pin;
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll, Waker};
use wgpu::util::DeviceExt;

/// Cells per workgroup side (8 x 8 = 64 invocations).
const WORKGROUP: u32 = 8;

/// The kernel source: the layout constants from Rust, then `kernel.wgsl`.
pub fn kernel_source() -> String {
    use offset::*;
    let consts = [
        ("HALF_STRIDE", HALF_STRIDE),
        ("NODES_PER_PANEL", NODES_PER_PANEL),
        ("OFF_WEIGHT", WEIGHT),
        ("OFF_M", M),
        ("OFF_K0", K0),
        ("OFF_DK", DK),
        ("OFF_C0", C0),
        ("OFF_DC", DC),
        ("OFF_KR", KR),
        ("OFF_CR", CR),
        ("OFF_YR", YR),
        ("OFF_OUT_Q", OUT_Q),
        ("OFF_OUT_V", OUT_V),
        ("OFF_OUT_A", OUT_A),
    ];
    let mut s: String = consts
        .iter()
        .map(|(name, v)| format!("const {name}: u32 = {v}u;\n"))
        .collect();
    s.push_str(include_str!("kernel.wgsl"));
    s
}

/// A GPU adapter with the kernel compiled, ready to map.
pub struct GpuMapper {
    device: wgpu::Device,
    queue: wgpu::Queue,
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    info: wgpu::AdapterInfo,
    max_storage: u64,
    uncaptured: Arc<Mutex<Option<String>>>,
}

impl std::fmt::Debug for GpuMapper {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuMapper")
            .field("adapter", &self.info.name)
            .field("backend", &self.info.backend)
            .finish()
    }
}

impl GpuMapper {
    /// The default adapter (high performance preferred) with the kernel compiled;
    /// `Ok(None)` when there is no adapter with compute shaders.
    pub async fn request() -> Result<Option<GpuMapper>> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let options = wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            ..Default::default()
        };
        let Ok(adapter) = instance.request_adapter(&options).await else {
            return Ok(None);
        };
        let caps = adapter.get_downlevel_capabilities();
        if !caps.flags.contains(wgpu::DownlevelFlags::COMPUTE_SHADERS) {
            return Ok(None);
        }
        let info = adapter.get_info();
        let limits = wgpu::Limits::downlevel_defaults();
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("ridelab"),
                required_limits: limits.clone(),
                ..Default::default()
            })
            .await
            .map_err(|e| RideError::Gpu(format!("no device on {}: {e}", info.name)))?;
        let uncaptured = Arc::new(Mutex::new(None));
        let sink = uncaptured.clone();
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            if let Ok(mut slot) = sink.lock() {
                slot.get_or_insert_with(|| e.to_string());
            }
        }));
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("ridelab hifi map"),
            source: wgpu::ShaderSource::Wgsl(kernel_source().into()),
        });
        let storage = |binding: u32, read_only: bool| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ridelab hifi map"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
                storage(1, true),
                storage(2, true),
                storage(3, true),
                storage(4, false),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("ridelab hifi map"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("ridelab hifi map"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        if let Some(e) = scope.pop().await {
            return Err(RideError::Gpu(format!(
                "the kernel does not compile on {}: {e}",
                info.name
            )));
        }
        Ok(Some(GpuMapper {
            device,
            queue,
            pipeline,
            layout,
            info,
            max_storage: limits.max_storage_buffer_binding_size,
            uncaptured,
        }))
    }

    /// The adapter's name, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
    pub fn adapter_name(&self) -> &str {
        &self.info.name
    }

    /// The graphics API in use ("vulkan", "metal", "dx12", "webgpu").
    pub fn backend(&self) -> String {
        self.info.backend.to_string()
    }

    /// True for a CPU implementation (lavapipe, SwiftShader, WARP): correct, not fast
    /// (the native `--compute auto` passes over one; the page asks for WebGPU's adapter).
    #[cfg(not(target_arch = "wasm32"))]
    pub(crate) fn is_software(&self) -> bool {
        self.info.device_type == wgpu::DeviceType::Cpu
    }

    /// The criteria of every cell of `input`'s grid (row-major, Cs rows), computed on
    /// the GPU. Errors name the cell whose value is not finite, or the device's failure.
    pub async fn run(&self, input: &MapInput) -> Result<Vec<Criteria>> {
        let grid = &input.grid;
        let cells = grid.len();
        let out_bytes = (cells * 3 * 4) as u64;
        if out_bytes > self.max_storage {
            return Err(RideError::field(
                "grid",
                format!(
                    "{} x {} cells need {out_bytes} bytes, more than the device's {} for one buffer",
                    grid.ks.n, grid.cs.n, self.max_storage
                ),
            ));
        }
        let halves: Vec<f32> = input.packed_halves::<f32>().concat();
        let (combined, split) = input.packed_nodes::<f32>();
        let nodes: Vec<f32> = combined.iter().chain(&split).flatten().copied().collect();
        let axes: Vec<f32> = grid
            .ks
            .values()
            .iter()
            .chain(&grid.cs.values())
            .map(|&v| v as f32)
            .collect();
        let params: [u32; 8] = [
            grid.ks.n as u32,
            grid.cs.n as u32,
            input.halves.len() as u32,
            combined.len() as u32,
            split.len() as u32,
            0,
            0,
            0,
        ];
        let d = &self.device;
        let scope = d.push_error_scope(wgpu::ErrorFilter::Validation);
        let memory = d.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let init = |label: &str, bytes: Vec<u8>, usage: wgpu::BufferUsages| {
            d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: &bytes,
                usage,
            })
        };
        let storage = wgpu::BufferUsages::STORAGE;
        let params = init(
            "params",
            params.iter().flat_map(|v| v.to_le_bytes()).collect(),
            wgpu::BufferUsages::UNIFORM,
        );
        let halves = init("halves", bytes(&halves), storage);
        let nodes = init("nodes", bytes(&nodes), storage);
        let axes = init("axes", bytes(&axes), storage);
        let out = d.create_buffer(&wgpu::BufferDescriptor {
            label: Some("out"),
            size: out_bytes,
            usage: storage | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let readback = d.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: out_bytes,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind = d.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ridelab hifi map"),
            layout: &self.layout,
            entries: &[&params, &halves, &nodes, &axes, &out]
                .iter()
                .enumerate()
                .map(|(k, b)| wgpu::BindGroupEntry {
                    binding: k as u32,
                    resource: b.as_entire_binding(),
                })
                .collect::<Vec<_>>(),
        });
        let mut encoder = d.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("ridelab hifi map"),
        });
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("ridelab hifi map"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &bind, &[]);
            pass.dispatch_workgroups(
                (grid.ks.n as u32).div_ceil(WORKGROUP),
                (grid.cs.n as u32).div_ceil(WORKGROUP),
                1,
            );
        }
        encoder.copy_buffer_to_buffer(&out, 0, &readback, 0, out_bytes);
        self.queue.submit([encoder.finish()]);
        let (tx, rx) = oneshot();
        readback
            .slice(..)
            .map_async(wgpu::MapMode::Read, move |r| tx.send(r.is_ok()));
        // Natively this drives the work to completion; on the web it does nothing and
        // the browser calls back.
        let polled = d.poll(wgpu::PollType::wait_indefinitely());
        let failed =
            |what: &str| -> RideError { RideError::Gpu(format!("{what} on {}", self.info.name)) };
        if let Err(e) = polled {
            return Err(RideError::Gpu(format!("{e} on {}", self.info.name)));
        }
        let mapped = rx.await;
        if let Some(e) = memory.pop().await {
            return Err(RideError::Gpu(format!("out of memory: {e}")));
        }
        if let Some(e) = scope.pop().await {
            return Err(RideError::Gpu(format!("{e}")));
        }
        if let Some(e) = self.uncaptured.lock().ok().and_then(|mut s| s.take()) {
            return Err(RideError::Gpu(e));
        }
        if !mapped {
            return Err(failed("reading the map back failed (device lost?)"));
        }
        let var: Vec<f32> = {
            let view = readback
                .slice(..)
                .get_mapped_range()
                .map_err(|e| RideError::Gpu(format!("reading the map back: {e}")))?;
            view.chunks_exact(4)
                .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
                .collect()
        };
        readback.unmap();
        var.chunks_exact(3)
            .enumerate()
            .map(|(k, v)| input.criteria(k, [v[0] as f64, v[1] as f64, v[2] as f64]))
            .collect()
    }
}

#[cfg(not(target_arch = "wasm32"))]
impl GpuMapper {
    /// [`GpuMapper::request`], blocking (native).
    pub fn new() -> Result<Option<GpuMapper>> {
        pollster::block_on(GpuMapper::request())
    }

    /// [`GpuMapper::run`], blocking (native).
    pub fn map(&self, input: &MapInput) -> Result<Vec<Criteria>> {
        pollster::block_on(self.run(input))
    }
}

fn bytes(v: &[f32]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

/// A one-value channel whose receiver is a future: the buffer-mapping callback sends,
/// the map awaits (natively after `poll` has already run the callback; in the browser
/// when the event loop does).
fn oneshot() -> (Sender, Receiver) {
    let shared = Arc::new(Mutex::new((None, None)));
    (Sender(shared.clone()), Receiver(shared))
}

type Slot = Arc<Mutex<(Option<bool>, Option<Waker>)>>;

struct Sender(Slot);

impl Sender {
    fn send(self, v: bool) {
        if let Ok(mut s) = self.0.lock() {
            s.0 = Some(v);
            if let Some(w) = s.1.take() {
                w.wake();
            }
        }
    }
}

struct Receiver(Slot);

impl Future for Receiver {
    type Output = bool;
    fn poll(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<bool> {
        match self.0.lock() {
            Ok(mut s) => match s.0.take() {
                Some(v) => Poll::Ready(v),
                None => {
                    s.1 = Some(cx.waker().clone());
                    Poll::Pending
                }
            },
            Err(_) => Poll::Ready(false),
        }
    }
}
