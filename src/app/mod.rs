//! The interactive viewer: a winit window that tessellates and draws the scene every
//! frame, with pan / zoom / fit (2D) or orbit / pan / dolly (3D), an egui side panel, and
//! editing.
//!
//! Mouse: left drag on a control point moves it; left drag on a Bézier curve pulls the
//! curve through the pointer (paper 000's least-squares single-target modification);
//! elsewhere left drag pans (2D) or orbits (3D); right or middle drag pans; the wheel
//! zooms at the cursor. Keys: `F` fit, `P` control polygons, `C` control points, `H`
//! panel, `Ctrl+Z` undo, `Ctrl+Shift+Z` / `Ctrl+Y` redo, `Ctrl+S` save, `Esc` quit.

pub mod edit;
mod stress;
mod ui;

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use glam::{DVec2, DVec3};
use thiserror::Error;
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{Key, ModifiersState, NamedKey};
use winit::window::{Window, WindowId};

use crate::camera::Camera;
use crate::geom::Lower;
use crate::gpu::pack::{
    ChunkLimits, PreparedScene, prepare_overlays, prepare_scene, repack_points,
};
use crate::gpu::renderer::{GpuScene, Renderer, camera_uniform};
use crate::gpu::tessellator::Tessellator;
use crate::gpu::{BackendChoice, ContextOptions, GpuContext, GpuError};
use crate::scene::Scene;

/// What to show and how.
#[derive(Debug, Clone)]
pub struct ViewOptions {
    /// The scene.
    pub scene: Scene,
    /// Exit after this many presented frames (smoke tests).
    pub frames: Option<u64>,
    /// The graphics API.
    pub backend: BackendChoice,
    /// Stress mode: re-solve every curve each frame (single target, paper 000) with its
    /// target circling the curve's midpoint. Needs a scene of Bézier curves of one degree.
    /// Editing is off in this mode.
    pub solve: bool,
    /// Where `Ctrl+S` saves the edited scene (`None`: `splinescope-scene.json` in the
    /// current directory).
    pub path: Option<PathBuf>,
}

/// Where an unnamed scene is saved.
pub const DEFAULT_SAVE_NAME: &str = "splinescope-scene.json";

/// Why the viewer stopped with an error.
#[derive(Debug, Error)]
pub enum AppError {
    /// The windowing system failed.
    #[error("window system: {0}")]
    Window(String),
    /// GPU setup or work failed.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// The window surface could not be used.
    #[error("window surface: {0}")]
    Surface(String),
}

/// Whether a display seems reachable (Linux/BSD: `DISPLAY` or `WAYLAND_DISPLAY` set).
#[must_use]
pub fn display_available() -> bool {
    if cfg!(any(
        target_os = "linux",
        target_os = "freebsd",
        target_os = "openbsd"
    )) {
        ["DISPLAY", "WAYLAND_DISPLAY"]
            .iter()
            .any(|v| std::env::var_os(v).is_some_and(|s| !s.is_empty()))
    } else {
        true
    }
}

/// Opens the window and runs until it is closed (or `frames` frames were presented).
///
/// # Errors
/// [`AppError`] when the window, the surface or the GPU fails.
pub fn run(opts: ViewOptions) -> Result<(), AppError> {
    let event_loop = EventLoop::new().map_err(|e| AppError::Window(e.to_string()))?;
    let mut app = App {
        opts,
        running: None,
        error: None,
    };
    event_loop
        .run_app(&mut app)
        .map_err(|e| AppError::Window(e.to_string()))?;
    match app.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

struct App {
    opts: ViewOptions,
    running: Option<Running>,
    error: Option<AppError>,
}

/// What the side panel can change.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Toggles {
    pub show_polygons: bool,
    pub show_points: bool,
    pub show_panel: bool,
}

struct Running {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    ctx: GpuContext,
    renderer: Renderer,
    gpu_scene: GpuScene,
    prepared: PreparedScene,
    editor: edit::Editor,
    camera: Camera,
    toggles: Toggles,
    uploaded_toggles: Toggles,
    egui_ctx: egui::Context,
    egui_state: egui_winit::State,
    egui_renderer: egui_wgpu::Renderer,
    cursor: DVec2,
    dragging: Option<MouseButton>,
    /// The point being edited by the left drag (its depth anchors 3D drags).
    editing: Option<DVec3>,
    modifiers: ModifiersState,
    /// Keep fitting the scene (to the area the panel leaves) until the user moves the
    /// camera; `F` turns it back on.
    auto_fit: bool,
    panel_width_px: f64,
    frames_presented: u64,
    fps: ui::FpsCounter,
    adapter: String,
    summaries: Vec<ui::CurveSummary>,
    stress: Option<stress::StressSolver>,
    started: Instant,
}

/// `SPLINESCOPE_LOSE_DEVICE_AFTER_FRAMES=N`: destroy the device after `N` presented
/// frames, to exercise the viewer's device-failure path.
fn lose_device_after() -> Option<u64> {
    std::env::var("SPLINESCOPE_LOSE_DEVICE_AFTER_FRAMES")
        .ok()
        .and_then(|v| v.parse().ok())
}

impl App {
    fn fail(&mut self, event_loop: &ActiveEventLoop, e: AppError) {
        self.error = Some(e);
        event_loop.exit();
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_some() {
            return;
        }
        match Running::new(event_loop, &self.opts) {
            Ok(r) => {
                r.window.request_redraw();
                self.running = Some(r);
            }
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(r) = self.running.as_mut() else {
            return;
        };
        let consumed = r.egui_state.on_window_event(&r.window, &event).consumed;
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => r.resize(size),
            WindowEvent::ScaleFactorChanged { .. } => r.resize(r.window.inner_size()),
            WindowEvent::RedrawRequested => {
                match r.frame() {
                    Ok(presented) => {
                        if presented {
                            r.frames_presented += 1;
                            // Forcing the device-failure path (tests and diagnosis): lose
                            // the device after N frames; the next frame must stop with a
                            // clear error.
                            if lose_device_after().is_some_and(|n| r.frames_presented == n) {
                                r.ctx.device.destroy();
                            }
                        }
                    }
                    Err(e) => {
                        self.fail(event_loop, e);
                        return;
                    }
                }
                if self.opts.frames.is_some_and(|n| r.frames_presented >= n) {
                    event_loop.exit();
                    return;
                }
                r.window.request_redraw();
            }
            WindowEvent::ModifiersChanged(m) => r.modifiers = m.state(),
            WindowEvent::CursorMoved { position, .. } => {
                let p = DVec2::new(position.x, position.y);
                let delta = p - r.cursor;
                r.cursor = p;
                let viewport = r.viewport();
                if let Some(anchor) = r.editing {
                    let world = r.camera.drag_point(p, viewport, anchor);
                    r.editor.drag_to(world);
                    return;
                }
                match r.dragging {
                    Some(MouseButton::Left) if r.camera.is_3d() => r.camera.orbit(delta),
                    Some(_) => r.camera.pan(delta, viewport),
                    None => {}
                }
                if r.dragging.is_some() {
                    r.auto_fit = false;
                }
            }
            WindowEvent::MouseInput { state, button, .. } => match state {
                ElementState::Pressed if !consumed => {
                    if button == MouseButton::Left && r.begin_edit() {
                        return;
                    }
                    r.dragging = Some(button);
                }
                ElementState::Released => {
                    r.dragging = None;
                    if r.editing.take().is_some() {
                        r.editor.finish();
                    }
                }
                ElementState::Pressed => {}
            },
            WindowEvent::MouseWheel { delta, .. } if !consumed => {
                let lines = match delta {
                    MouseScrollDelta::LineDelta(_, y) => f64::from(y),
                    MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
                };
                let viewport = r.viewport();
                r.camera.zoom_at(1.15_f64.powf(lines), r.cursor, viewport);
                r.auto_fit = false;
            }
            WindowEvent::KeyboardInput { event, .. }
                if !consumed && event.state == ElementState::Pressed =>
            {
                let ctrl = r.modifiers.control_key() || r.modifiers.super_key();
                let shift = r.modifiers.shift_key();
                match event.logical_key.as_ref() {
                    Key::Character("z" | "Z") if ctrl && !shift => {
                        r.editor.undo();
                    }
                    Key::Character("z" | "Z") if ctrl => {
                        r.editor.redo();
                    }
                    Key::Character("y" | "Y") if ctrl => {
                        r.editor.redo();
                    }
                    Key::Character("s" | "S") if ctrl => r.save(),
                    Key::Named(NamedKey::Escape) => event_loop.exit(),
                    Key::Character("f" | "F") => {
                        r.auto_fit = true;
                        r.fit();
                    }
                    Key::Character("p" | "P") => r.toggles.show_polygons ^= true,
                    Key::Character("c" | "C") => r.toggles.show_points ^= true,
                    Key::Character("h" | "H") => r.toggles.show_panel ^= true,
                    _ => {}
                }
            }
            _ => {}
        }
    }
}

impl Running {
    fn new(event_loop: &ActiveEventLoop, opts: &ViewOptions) -> Result<Running, AppError> {
        let title = format!(
            "splinescope — {}",
            opts.scene.name.as_deref().unwrap_or("scene")
        );
        let window = Arc::new(
            event_loop
                .create_window(
                    Window::default_attributes()
                        .with_title(title)
                        .with_inner_size(PhysicalSize::new(1280, 800)),
                )
                .map_err(|e| AppError::Window(e.to_string()))?,
        );
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends: opts.backend.backends(),
            ..wgpu::InstanceDescriptor::new_with_display_handle_from_env(Box::new(
                event_loop.owned_display_handle(),
            ))
        });
        let surface = instance
            .create_surface(window.clone())
            .map_err(|e| AppError::Surface(e.to_string()))?;
        let ctx = GpuContext::with_instance(
            instance,
            &ContextOptions::from_env(opts.backend),
            Some(&surface),
        )?;
        let size = window.inner_size();
        let caps = surface.get_capabilities(&ctx.adapter);
        // Colours are sRGB values blended as such (like the offscreen images), so a
        // non-sRGB format is preferred; egui prefers it too.
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| !f.is_srgb())
            .or_else(|| caps.formats.first().copied())
            .ok_or_else(|| AppError::Surface("the surface offers no format".into()))?;
        let mut config = surface
            .get_default_config(&ctx.adapter, size.width.max(1), size.height.max(1))
            .ok_or_else(|| AppError::Surface("the adapter cannot present to this window".into()))?;
        config.format = format;
        config.present_mode = wgpu::PresentMode::AutoVsync;
        surface.configure(&ctx.device, &config);

        let renderer = Renderer::new(&ctx.device, format);
        let toggles = Toggles {
            show_polygons: true,
            show_points: true,
            show_panel: true,
        };
        let scene = opts.scene.clone();
        let (gpu_scene, prepared) = upload(&ctx, &ctx.tessellator, &renderer, &scene, toggles)?;
        let editor = edit::Editor::new(
            scene.clone(),
            Some(
                opts.path
                    .clone()
                    .unwrap_or_else(|| PathBuf::from(DEFAULT_SAVE_NAME)),
            ),
        );
        let stress = if opts.solve {
            let chunk_points: Vec<usize> = prepared.chunks.iter().map(|c| c.points.len()).collect();
            Some(
                stress::StressSolver::new(&scene, &prepared.placements, &chunk_points).ok_or_else(|| {
                    AppError::Surface(
                        "solve mode needs a scene of Bézier curves of one degree ≥ 2 (use --stress)".into(),
                    )
                })?,
            )
        } else {
            None
        };
        let egui_ctx = egui::Context::default();
        let egui_state = egui_winit::State::new(
            egui_ctx.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(ctx.device.limits().max_texture_dimension_2d as usize),
        );
        let egui_renderer =
            egui_wgpu::Renderer::new(&ctx.device, format, egui_wgpu::RendererOptions::default());
        let adapter = ctx.describe();
        let viewport = DVec2::new(f64::from(config.width), f64::from(config.height));
        let camera = scene.camera(viewport);
        let mut running = Running {
            window,
            surface,
            config,
            ctx,
            renderer,
            gpu_scene,
            prepared,
            editor,
            camera,
            toggles,
            uploaded_toggles: toggles,
            egui_ctx,
            egui_state,
            egui_renderer,
            cursor: DVec2::ZERO,
            dragging: None,
            editing: None,
            modifiers: ModifiersState::empty(),
            auto_fit: opts.scene.view == crate::scene::ViewSpec::Auto,
            panel_width_px: ui::PANEL_WIDTH_POINTS,
            frames_presented: 0,
            fps: ui::FpsCounter::new(Instant::now()),
            adapter,
            summaries: ui::summarize(&opts.scene),
            stress,
            started: Instant::now(),
        };
        if running.auto_fit {
            running.fit();
        }
        Ok(running)
    }

    fn viewport(&self) -> DVec2 {
        DVec2::new(f64::from(self.config.width), f64::from(self.config.height))
    }

    /// Fits the scene into the part of the window the panel leaves free.
    fn fit(&mut self) {
        let viewport = self.viewport();
        let panel = if self.toggles.show_panel {
            self.panel_width_px.min(viewport.x * 0.5)
        } else {
            0.0
        };
        let free = DVec2::new((viewport.x - panel).max(1.0), viewport.y);
        let scene = self.editor.scene();
        self.camera = Camera::fit(scene.bounds(), free, !scene.is_planar());
        // Keep the scale fitted to the free area, centred in it.
        if let Camera::Ortho2d(c) = &mut self.camera {
            c.center.x -= 0.5 * panel / c.pixels_per_unit;
        }
    }

    /// Starts an edit under the pointer (a control point, or a Bézier curve to pull);
    /// `false` when there is nothing to edit there.
    fn begin_edit(&mut self) -> bool {
        if self.stress.is_some() {
            return false;
        }
        let radius = 9.0 * self.window.scale_factor();
        let hit = self.editor.pick(
            &self.camera,
            self.viewport(),
            self.cursor,
            radius,
            self.toggles.show_points,
        );
        match hit {
            Some(edit::Hit::Point { curve, index, at }) => {
                self.editor.begin_point_drag(curve, index);
                self.editing = Some(at);
                // The view stays put while the scene is edited.
                self.auto_fit = false;
                true
            }
            Some(edit::Hit::Curve { curve, t, at }) => match self.editor.begin_pull(curve, t) {
                Ok(()) => {
                    self.editing = Some(at);
                    self.auto_fit = false;
                    true
                }
                Err(message) => {
                    self.editor.message = Some(message);
                    false
                }
            },
            None => false,
        }
    }

    fn save(&mut self) {
        if let Err(message) = self.editor.save(None) {
            self.editor.message = Some(message);
        }
    }

    /// Brings the GPU up to date with edits and the panel's switches: curves whose
    /// lowering kept its structure are rewritten in place; otherwise the scene is packed
    /// again. Overlays are rebuilt when anything changed.
    fn sync_edits(&mut self) -> Result<(), AppError> {
        let changed = self.editor.take_changed();
        if changed.is_empty() && self.toggles == self.uploaded_toggles {
            return Ok(());
        }
        let shown = shown_scene(self.editor.scene(), self.toggles);
        let in_place = self.toggles == self.uploaded_toggles
            && changed.iter().all(|&c| {
                let segments = shown.curves[c].curve.lower();
                let writes = self
                    .prepared
                    .placements
                    .get(c)
                    .zip(self.prepared.sample_counts.get(c))
                    .and_then(|(p, n)| repack_points(p, n, &segments, shown.samples_for(c)));
                match writes {
                    Some(writes) => {
                        for (chunk, first, verts) in writes {
                            self.gpu_scene
                                .write_points(&self.ctx.queue, chunk, first, &verts);
                        }
                        true
                    }
                    None => false,
                }
            });
        if in_place {
            let limits = ChunkLimits::for_binding_size(self.ctx.max_binding_bytes());
            let (lines, points) = prepare_overlays(&shown, limits);
            self.renderer
                .replace_overlays(&self.ctx.device, &mut self.gpu_scene, &lines, &points);
        } else {
            let (gpu, prepared) = upload(
                &self.ctx,
                &self.ctx.tessellator,
                &self.renderer,
                self.editor.scene(),
                self.toggles,
            )?;
            self.gpu_scene = gpu;
            self.prepared = prepared;
            self.uploaded_toggles = self.toggles;
        }
        ui::refresh(&mut self.summaries, self.editor.scene(), &changed);
        Ok(())
    }

    fn resize(&mut self, size: PhysicalSize<u32>) {
        if size.width == 0 || size.height == 0 {
            return; // minimised: keep the old configuration, draw nothing
        }
        self.config.width = size.width;
        self.config.height = size.height;
        self.surface.configure(&self.ctx.device, &self.config);
    }

    /// Draws one frame. Returns whether a frame was presented (not when minimised or the
    /// surface had to be reconfigured).
    fn frame(&mut self) -> Result<bool, AppError> {
        let size = self.window.inner_size();
        if size.width == 0 || size.height == 0 {
            return Ok(false);
        }
        // A lost device stops the viewer with a clear error instead of a panic or a hang
        // (polling first delivers a pending loss notice).
        let _ = self.ctx.device.poll(wgpu::PollType::Poll);
        self.ctx.check_health()?;
        self.sync_edits()?;
        if let Some(s) = &mut self.stress {
            s.step(
                self.started.elapsed().as_secs_f64(),
                &self.ctx.queue,
                &self.gpu_scene,
            );
        }
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f)
            | wgpu::CurrentSurfaceTexture::Suboptimal(f) => f,
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => {
                return Ok(false);
            }
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.resize(size);
                return Ok(false);
            }
            wgpu::CurrentSurfaceTexture::Validation => {
                // A failed device is the likelier cause: say so when it is.
                self.ctx.check_health()?;
                return Err(AppError::Surface(
                    "validation error acquiring the frame".into(),
                ));
            }
        };
        let view = frame
            .texture
            .create_view(&wgpu::TextureViewDescriptor::default());
        let viewport = self.viewport();
        let scale = self.window.scale_factor() as f32;
        self.renderer.set_camera(
            &self.ctx.queue,
            &camera_uniform(&self.camera, viewport, scale),
        );

        // The panel.
        let raw = self.egui_state.take_egui_input(&self.window);
        self.fps.tick(Instant::now());
        let mut actions = ui::Actions::default();
        let info = ui::PanelInfo {
            summaries: &self.summaries,
            adapter: &self.adapter,
            fps: self.fps.fps(),
            samples_per_frame: self.gpu_scene.sample_count(),
            camera: &self.camera,
            solving: self.stress.as_ref().map(|s| (s.curves, s.last_solve_ms)),
        };
        let toggles = &mut self.toggles;
        let editor = &mut self.editor;
        let editable = self.stress.is_none();
        let mut panel_width = 0.0_f32;
        let output = self.egui_ctx.run_ui(raw, |ui| {
            panel_width = ui::panel(ui, &info, toggles, editor, editable, &mut actions);
        });
        self.panel_width_px = f64::from(panel_width) * f64::from(output.pixels_per_point);
        // A panel control's drag (a slider) is one edit: commit it when the pointer lets go.
        if self.editing.is_none() && self.egui_ctx.input(|i| i.pointer.any_released()) {
            self.editor.finish();
        }
        self.egui_state
            .handle_platform_output(&self.window, output.platform_output);
        let jobs = self
            .egui_ctx
            .tessellate(output.shapes, output.pixels_per_point);
        for (id, deltas) in &output.textures_delta.set {
            for delta in deltas {
                self.egui_renderer
                    .update_texture(&self.ctx.device, &self.ctx.queue, *id, delta);
            }
        }
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [self.config.width, self.config.height],
            pixels_per_point: output.pixels_per_point,
        };
        let mut encoder = self
            .ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("frame"),
            });
        let extra = self.egui_renderer.update_buffers(
            &self.ctx.device,
            &self.ctx.queue,
            &mut encoder,
            &jobs,
            &screen,
        );
        self.ctx.tessellator.encode(
            &mut encoder,
            self.gpu_scene.chunks.iter().map(|c| &c.buffers),
            None,
        );
        {
            let mut pass = self
                .renderer
                .begin_pass(
                    &mut encoder,
                    &view,
                    wgpu::LoadOp::Clear(self.gpu_scene.background),
                )
                .forget_lifetime();
            self.renderer.draw(&mut pass, &self.gpu_scene);
            self.egui_renderer.render(&mut pass, &jobs, &screen);
        }
        self.ctx
            .queue
            .submit(extra.into_iter().chain([encoder.finish()]));
        self.window.pre_present_notify();
        self.ctx.queue.present(frame);
        for id in &output.textures_delta.free {
            self.egui_renderer.free_texture(id);
        }
        if actions.fit {
            self.auto_fit = true;
        }
        if actions.save {
            self.save();
        }
        if self.auto_fit {
            // The panel's width is known only after it is drawn: fit to what it leaves.
            self.fit();
        }
        Ok(true)
    }
}

/// The scene with the panel's overlay switches applied.
fn shown_scene(scene: &Scene, toggles: Toggles) -> Scene {
    let mut shown = scene.clone();
    for c in &mut shown.curves {
        c.style.show_polygon &= toggles.show_polygons;
        c.style.show_points &= toggles.show_points;
    }
    shown
}

/// Prepares and uploads the scene with the panel's overlay switches applied.
fn upload(
    ctx: &GpuContext,
    tessellator: &Tessellator,
    renderer: &Renderer,
    scene: &Scene,
    toggles: Toggles,
) -> Result<(GpuScene, PreparedScene), AppError> {
    let shown = shown_scene(scene, toggles);
    let prepared = prepare_scene(
        &shown,
        ChunkLimits::for_binding_size(ctx.max_binding_bytes()),
    )
    .map_err(GpuError::from)?;
    Ok((
        renderer.upload(&ctx.device, tessellator, &prepared),
        prepared,
    ))
}
