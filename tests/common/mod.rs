//! Shared helpers of the integration tests.
#![allow(dead_code, missing_docs)]

use std::sync::OnceLock;

use splinescope_gpu::{BackendChoice, ContextOptions, GpuContext, GpuError, Pipelines};

/// The environment variable that lets GPU tests skip (and say so) when no adapter exists.
pub const SKIP_VAR: &str = "SPLINESCOPE_SKIP_GPU_TESTS";

/// The environment variable that lists the backends GPU tests run on
/// (`vulkan,gl`); by default every backend that has an adapter.
pub const BACKENDS_VAR: &str = "SPLINESCOPE_TEST_BACKENDS";

/// One backend's device, shared by the tests of a test binary.
pub struct Backend {
    /// `vulkan`, `gl`, `metal` or `dx12`: what `--gpu-backend` takes.
    pub name: String,
    /// Its context.
    pub ctx: GpuContext,
    /// The compute pipelines built on its device.
    pub pipelines: Pipelines,
}

const ALL: [BackendChoice; 4] = [
    BackendChoice::Vulkan,
    BackendChoice::Gl,
    BackendChoice::Metal,
    BackendChoice::Dx12,
];

fn open_all() -> Result<Vec<Backend>, String> {
    let listed = std::env::var(BACKENDS_VAR)
        .ok()
        .filter(|v| !v.trim().is_empty());
    let (choices, explicit) = match &listed {
        Some(list) => (
            list.split(',')
                .map(|s| {
                    s.trim()
                        .parse::<BackendChoice>()
                        .map_err(|e| format!("{BACKENDS_VAR}: {e}"))
                })
                .collect::<Result<Vec<_>, _>>()?,
            true,
        ),
        None => (ALL.to_vec(), false),
    };
    let mut found = Vec::new();
    let mut missing = Vec::new();
    for choice in choices {
        match GpuContext::new(&ContextOptions::from_env(choice)) {
            Ok((ctx, pipelines)) => found.push(Backend {
                name: choice.to_string(),
                ctx,
                pipelines,
            }),
            // Without a list, a backend with no adapter at all is simply not present; one
            // whose adapter was refused (a kernel computing wrong samples) is a failure.
            Err(GpuError::NoAdapter { .. }) if !explicit => {}
            Err(e) => missing.push(format!("{choice}: {e}")),
        }
    }
    if !missing.is_empty() {
        return Err(format!(
            "GPU backend(s) without a usable adapter: {}",
            missing.join("; ")
        ));
    }
    if found.is_empty() {
        return Err("no GPU adapter on any backend".into());
    }
    Ok(found)
}

/// Every backend the GPU tests run on, each with its context. Without an adapter this
/// fails the test with installation instructions, unless `SPLINESCOPE_SKIP_GPU_TESTS=1`
/// asks to skip: then it prints that the test was skipped and returns an empty list.
pub fn gpus(test: &str) -> Vec<&'static Backend> {
    static BACKENDS: OnceLock<Result<Vec<Backend>, String>> = OnceLock::new();
    match BACKENDS.get_or_init(open_all) {
        Ok(all) => all.iter().collect(),
        Err(e) if std::env::var(SKIP_VAR).is_ok_and(|v| v == "1") => {
            eprintln!("SKIPPED {test}: {e}; {SKIP_VAR}=1 asked to skip");
            Vec::new()
        }
        Err(e) => panic!(
            "{test} needs a GPU adapter: {e}\n\
             Install the software ones (Debian/Ubuntu: sudo apt-get install mesa-vulkan-drivers \
             libvulkan1 libegl1 libgl1-mesa-dri), choose backends with {BACKENDS_VAR}=vulkan,gl, \
             or set {SKIP_VAR}=1 to skip GPU tests explicitly."
        ),
    }
}

/// Runs `body` once per backend, saying which backend each run is on (the test's output
/// names the backend of a failure).
pub fn on_each_gpu(test: &str, mut body: impl FnMut(&'static Backend)) {
    for backend in gpus(test) {
        eprintln!(
            "{test}: on backend {} ({})",
            backend.name,
            backend.ctx.describe()
        );
        body(backend);
    }
}

/// Where tests write their output files (under `target/`).
pub fn out_dir(sub: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("target")
        .join("test-output")
        .join(sub);
    std::fs::create_dir_all(&dir).expect("create test output dir");
    dir
}

/// The splinescope binary under test.
pub fn bin() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_splinescope"))
}

/// Runs the binary with `args`.
pub fn run(args: &[&str]) -> std::process::Output {
    bin().args(args).output().expect("run splinescope")
}

/// Exit code, stdout and stderr of a run, for assertion messages.
pub fn text(out: &std::process::Output) -> String {
    format!(
        "exit {:?}\nstdout:\n{}\nstderr:\n{}",
        out.status.code(),
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    )
}

/// CRC-32 (ISO 3309, as PNG uses), written out here so that crafted PNG chunks do not
/// depend on the encoder under test.
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = 0xffff_ffff_u32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                0xedb8_8320 ^ (crc >> 1)
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// One PNG chunk: length, type, data, CRC.
pub fn png_chunk(kind: &[u8; 4], data: &[u8]) -> Vec<u8> {
    let mut out = (data.len() as u32).to_be_bytes().to_vec();
    let mut body = kind.to_vec();
    body.extend_from_slice(data);
    out.extend_from_slice(&body);
    out.extend_from_slice(&crc32(&body).to_be_bytes());
    out
}

/// The 8-byte PNG signature.
pub const PNG_SIGNATURE: [u8; 8] = [137, 80, 78, 71, 13, 10, 26, 10];

/// A PNG whose header declares `width × height` 8-bit RGBA pixels, followed by an empty
/// (valid) zlib stream and the end chunk: a few dozen bytes on disk, whatever it declares.
pub fn crafted_png_header(width: u32, height: u32) -> Vec<u8> {
    let mut ihdr = width.to_be_bytes().to_vec();
    ihdr.extend_from_slice(&height.to_be_bytes());
    ihdr.extend_from_slice(&[8, 6, 0, 0, 0]);
    let mut png = PNG_SIGNATURE.to_vec();
    png.extend(png_chunk(b"IHDR", &ihdr));
    // One stored, empty, final block and the Adler-32 of nothing.
    png.extend(png_chunk(
        b"IDAT",
        &[0x78, 0x01, 0x01, 0x00, 0x00, 0xff, 0xff, 0, 0, 0, 1],
    ));
    png.extend(png_chunk(b"IEND", &[]));
    png
}

/// A PNG of `data` with the given colour type and depth (and palette and tRNS entries),
/// written by the `png` encoder.
pub fn encode_png(
    (width, height): (u32, u32),
    color: png::ColorType,
    depth: png::BitDepth,
    data: &[u8],
    palette: Option<(&[u8], &[u8])>,
) -> Vec<u8> {
    let mut bytes = Vec::new();
    {
        let mut e = png::Encoder::new(&mut bytes, width, height);
        e.set_color(color);
        e.set_depth(depth);
        if let Some((plte, trns)) = palette {
            e.set_palette(plte.to_vec());
            if !trns.is_empty() {
                e.set_trns(trns.to_vec());
            }
        }
        let mut w = e.write_header().unwrap();
        w.write_image_data(data).unwrap();
        w.finish().unwrap();
    }
    bytes
}

/// `scene` encoded and packed into chunks that fit `ctx`'s storage bindings.
pub fn pack(
    ctx: &GpuContext,
    scene: &splinescope_scene::format::Scene,
) -> splinescope_gpu::pack::PreparedScene {
    splinescope_gpu::pack::prepare(
        &splinescope_scene::format::encoding::encode(scene),
        splinescope_gpu::chunks::ChunkLimits::for_binding_size(ctx.max_binding_bytes()),
    )
    .expect("pack")
}

/// An SVG rasterised by resvg (the figures' independent renderer), `w × h` pixels.
pub fn rasterise_svg(text: &str, w: u32, h: u32) -> splinescope_image::RgbaImage {
    let tree = resvg::usvg::Tree::from_str(text, &resvg::usvg::Options::default())
        .expect("the SVG parses");
    let mut pixmap = resvg::tiny_skia::Pixmap::new(w, h).expect("pixmap");
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::default(),
        &mut pixmap.as_mut(),
    );
    // The background is opaque: premultiplied equals straight alpha.
    splinescope_image::RgbaImage {
        width: w,
        height: h,
        data: pixmap.data().to_vec(),
    }
}

/// `scene` drawn through the one render entry point ([`splinescope_render::render`]) at
/// `width × height`, through `camera` (the scene's own view when `None`), with no
/// overlays or text; the GPU's error as such (a request of these values can fail no
/// other way).
pub fn render_scene(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    scene: &splinescope_scene::format::Scene,
    camera: Option<splinescope_encoding::camera::Camera>,
    width: u32,
    height: u32,
) -> Result<splinescope_image::RgbaImage, GpuError> {
    let mut request = splinescope_render::RenderRequest::new(width, height);
    request.camera = camera;
    splinescope_render::render(ctx, pipelines, scene, &request).map_err(|e| match e {
        splinescope_render::RenderError::Gpu(e) => e,
        other => panic!("a render request of {width}×{height} was refused: {other}"),
    })
}
