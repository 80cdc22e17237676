//! The window: winit events turned into [`crate::interaction::Input`], a frame composed
//! from the scene on the GPU and the egui panel (with the `window` feature, on by
//! default).

use std::path::PathBuf;
use std::time::Instant;

use glam::DVec2;
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{Key, ModifiersState, NamedKey};
use winit::window::WindowId;

use crate::app_error::AppError;
use crate::egui_layer::{self, EguiLayer};
use crate::interaction::{Button, Input, Interaction, Toggles};
use crate::scene_view::SceneView;
use crate::surface::WindowSurface;
use crate::{digest, edit, file_dialog, interaction, stress, timing, ui};
use splinescope_gpu::renderer::camera_uniform;
use splinescope_gpu::{BackendChoice, ContextOptions, GpuContext, GpuError};
use splinescope_scene::format::Scene;

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
    /// The tessellation tolerance in pixels (see [`splinescope_gpu::adaptive`]).
    pub tolerance_px: f64,
    /// Start with control polygons and points hidden (`P`, `C` show them): the stress
    /// scenes, whose overlays would cover the curves.
    pub overlays_hidden: bool,
    /// The scene's file, where `Ctrl+S` saves it. `None` (the gallery, the stress
    /// scenes): the scene is no file's, and `Ctrl+S` asks where in the save-as dialog
    /// (proposing [`DEFAULT_SAVE_NAME`], which is replaced only when confirmed).
    pub path: Option<PathBuf>,
    /// The text `scene` was read from at `path` ([`Scene::read`]), so that saving keeps
    /// the file's form; `None` for a scene that is not a file's (the gallery, stress).
    pub source: Option<String>,
    /// Start with every curve's curvature comb on (`K` turns it off), at the scale given
    /// (`None`: chosen for the view).
    pub comb: Option<Option<f64>>,
    /// The longest comb hair, a fraction of the view's height.
    pub comb_cap: splinescope_scene::format::shape::CombCap,
    /// Destroy the device after this many presented frames, to exercise the viewer's
    /// device-failure path (`view --lose-device-after-frames N`, for its smoke test);
    /// `None` normally.
    pub lose_device_after_frames: Option<u64>,
}

pub use file_dialog::DEFAULT_SAVE_NAME;

/// The editor of the scene `opts` shows: saving to its file when it has one (keeping the
/// file's form), to no file otherwise — a scene that did not come from a file never
/// overwrites one without asking.
#[must_use]
pub fn editor_for(opts: &ViewOptions, scene: Scene) -> edit::Editor {
    match (&opts.path, &opts.source) {
        (Some(path), Some(text)) => edit::Editor::of_file(scene, path.clone(), text.clone()),
        (path, _) => edit::Editor::new(scene, path.clone()),
    }
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
pub fn run(opts: ViewOptions) -> Result<ViewStats, AppError> {
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
        None => Ok(app
            .running
            .as_ref()
            .map_or_else(ViewStats::default, Running::stats)),
    }
}

/// What `view … --stats` prints at exit: the frame rate over the frames presented (from
/// the first), the last figures the GPU reported, and the mean milliseconds per stage
/// (GPU timestamps where the adapter has them; `solve` is the CPU's stress solve).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct ViewStats {
    /// Frames presented.
    pub frames: u64,
    /// Frames per second, from the first frame presented to the last.
    pub fps: f64,
    /// Samples the adaptive tessellation drew in a recent frame.
    pub samples_per_frame: u64,
    /// Line pieces drawn for the curves in a recent frame.
    pub line_pieces_per_frame: u64,
    /// Mean milliseconds per stage: `count`, `scan`, `tessellate`, `draw` (scene and
    /// panel) on the GPU, `solve` on the CPU in stress-solve mode.
    pub stage_ms: std::collections::BTreeMap<&'static str, f64>,
    /// The tolerance in pixels at exit.
    pub tolerance_px: f64,
    /// Whether a recent frame was coarsened to fit the sample buffers.
    pub capped: bool,
    /// The adapter.
    pub adapter: String,
}

struct App {
    opts: ViewOptions,
    running: Option<Running>,
    error: Option<AppError>,
}

/// A viewer with its window open.
struct Running {
    surface: WindowSurface,
    ctx: GpuContext,
    view: SceneView,
    egui: EguiLayer,
    model: Interaction,
    modifiers: ModifiersState,
    frames_presented: u64,
    fps: digest::FpsCounter,
    adapter: String,
    stress: Option<stress::StressSolver>,
    started: Instant,
    timer: Option<timing::StageTimer>,
    /// When the first frame was presented (the `--stats` frame rate counts from it).
    first_presented: Option<Instant>,
    last_presented: Option<Instant>,
    /// Milliseconds of every stress solve, summed, and their number.
    solve_ms: (f64, u32),
    /// The window's title as last set.
    title: String,
}

impl App {
    fn fail(&mut self, event_loop: &ActiveEventLoop, e: AppError) {
        self.error = Some(e);
        event_loop.exit();
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let Some(r) = self.running.as_mut() else {
            return;
        };
        match r.frame() {
            Ok(true) => {
                r.frames_presented += 1;
                let now = Instant::now();
                r.first_presented.get_or_insert(now);
                r.last_presented = Some(now);
                // Forcing the device-failure path (tests and diagnosis): lose the device
                // after N frames; the next frame must stop with a clear error.
                if self
                    .opts
                    .lose_device_after_frames
                    .is_some_and(|n| r.frames_presented == n)
                {
                    r.ctx.device.destroy();
                }
            }
            Ok(false) => {}
            Err(e) => {
                self.fail(event_loop, e);
                return;
            }
        }
        if r.model.exit_requested || self.opts.frames.is_some_and(|n| r.frames_presented >= n) {
            event_loop.exit();
            return;
        }
        r.surface.window.request_redraw();
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_some() {
            return;
        }
        match Running::new(event_loop, &self.opts) {
            Ok(r) => {
                r.surface.window.request_redraw();
                self.running = Some(r);
            }
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(r) = self.running.as_mut() else {
            return;
        };
        let consumed = r.egui.on_window_event(&r.surface.window, &event);
        let input = match event {
            WindowEvent::CloseRequested => {
                if r.model.request_close().exit {
                    event_loop.exit();
                }
                return;
            }
            WindowEvent::Resized(_) | WindowEvent::ScaleFactorChanged { .. } => {
                r.surface.resize(&r.ctx);
                r.model.viewport = r.surface.viewport();
                r.model.scale_factor = r.surface.window.scale_factor();
                return;
            }
            WindowEvent::RedrawRequested => {
                self.redraw(event_loop);
                return;
            }
            WindowEvent::DroppedFile(path) => {
                r.model.open_path(&path);
                return;
            }
            WindowEvent::ModifiersChanged(m) => {
                r.modifiers = m.state();
                return;
            }
            WindowEvent::CursorMoved { position, .. } => {
                Input::PointerMoved(DVec2::new(position.x, position.y))
            }
            WindowEvent::MouseInput { state, button, .. } => match state {
                ElementState::Pressed if !consumed => Input::Pressed(match button {
                    MouseButton::Left => Button::Primary,
                    MouseButton::Middle => Button::Middle,
                    _ => Button::Secondary,
                }),
                ElementState::Released => Input::Released,
                ElementState::Pressed => return,
            },
            WindowEvent::MouseWheel { delta, .. } if !consumed => Input::Wheel(match delta {
                MouseScrollDelta::LineDelta(_, y) => f64::from(y),
                MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
            }),
            WindowEvent::KeyboardInput { event, .. }
                if !consumed && event.state == ElementState::Pressed =>
            {
                let key = match event.logical_key.as_ref() {
                    Key::Named(NamedKey::Escape) => interaction::Key::Escape,
                    Key::Named(NamedKey::F1) => interaction::Key::Help,
                    Key::Named(NamedKey::Delete | NamedKey::Backspace) => interaction::Key::Delete,
                    Key::Character(s) => match s.chars().next() {
                        Some(c) => interaction::Key::Char(c),
                        None => return,
                    },
                    _ => return,
                };
                Input::Key {
                    key,
                    ctrl: r.modifiers.control_key() || r.modifiers.super_key(),
                    shift: r.modifiers.shift_key(),
                }
            }
            _ => return,
        };
        if r.model.handle(input).exit {
            event_loop.exit();
        }
    }
}

impl Running {
    fn new(event_loop: &ActiveEventLoop, opts: &ViewOptions) -> Result<Running, AppError> {
        let title = format!(
            "splinescope — {}",
            opts.scene.name.as_deref().unwrap_or("scene")
        );
        let (surface, ctx, pipelines) =
            WindowSurface::open(event_loop, &title, &ContextOptions::from_env(opts.backend))?;
        let scene = opts.scene.clone();
        let mut toggles = Toggles::default();
        if opts.overlays_hidden || opts.solve {
            toggles.show_polygons = false;
            toggles.show_points = false;
        }
        let view = SceneView::new(&ctx, &pipelines, surface.format(), &scene, toggles)?;
        let stress = if opts.solve {
            let chunk_points: Vec<usize> = view
                .prepared
                .chunks
                .iter()
                .map(|c| c.points.len())
                .collect();
            Some(
                stress::StressSolver::new(&scene, &view.prepared.placements, &chunk_points)
                    .ok_or_else(|| {
                        AppError::Surface(
                            "solve mode needs a scene of Bézier curves of one degree ≥ 2 (use --stress)"
                                .into(),
                        )
                    })?,
            )
        } else {
            None
        };
        let egui = EguiLayer::new(&surface.window, &ctx, surface.format());
        let editor = editor_for(opts, scene);
        let mut model = Interaction::new(
            editor,
            surface.viewport(),
            surface.window.scale_factor(),
            ui::PANEL_WIDTH_POINTS,
        );
        model.editable = stress.is_none();
        model.recent = file_dialog::RecentFiles::load(file_dialog::RecentFiles::default_store());
        if model.editable {
            if let Some(path) = opts.path.as_deref().filter(|p| p.is_file())
                && let Err(e) = model.recent.add(path)
            {
                model.editor.message = Some(e.to_string());
            }
            model.offer_recovery();
        }
        model.tolerance_px = opts.tolerance_px;
        model.toggles = toggles;
        model.shape.comb_cap = opts.comb_cap;
        if let Some(scale) = opts.comb {
            if let Some(s) = scale {
                model.shape.set_comb_scale(s).map_err(AppError::Surface)?;
            }
            model.toggle_comb();
        }
        if stress.is_some() {
            model.overlays_locked = Some(
                "the solver moves every control point on the GPU each frame: polygons and points are not drawn while solving",
            );
        }
        let title = model.editor.title();
        surface.window.set_title(&title);
        Ok(Running {
            title,
            timer: timing::StageTimer::new(&ctx),
            first_presented: None,
            last_presented: None,
            solve_ms: (0.0, 0),
            adapter: ctx.describe(),
            surface,
            ctx,
            view,
            egui,
            model,
            modifiers: ModifiersState::empty(),
            frames_presented: 0,
            fps: digest::FpsCounter::new(Instant::now()),
            stress,
            started: Instant::now(),
        })
    }

    /// Draws one frame. Returns whether a frame was presented (not when minimised or the
    /// surface had to be reconfigured).
    fn frame(&mut self) -> Result<bool, AppError> {
        let size = self.surface.window.inner_size();
        if size.width == 0 || size.height == 0 {
            return Ok(false);
        }
        // A lost device stops the viewer with a clear error instead of a panic or a hang
        // (polling first delivers a pending loss notice).
        let _ = self.ctx.device.poll(wgpu::PollType::Poll);
        self.ctx.check_health()?;
        self.view.poll_stats(&self.ctx);
        if let Some(t) = &mut self.timer {
            t.poll();
        }
        let changed = self.model.editor.take_changed();
        if let Err(e) = self.view.sync(
            &self.ctx,
            self.model.editor.scene(),
            &changed,
            self.model.toggles,
        ) {
            // A scene the GPU cannot take (an edit no check refused where it was made):
            // the edit is undone and said, never the end of the session.
            let AppError::Gpu(GpuError::Pack(why)) = e else {
                return Err(e);
            };
            if !self.model.editor.undo() {
                return Err(AppError::Gpu(GpuError::Pack(why)));
            }
            self.model.editor.warning = Some(format!("{why} — the edit was undone"));
            let changed = self.model.editor.take_changed();
            self.view.sync(
                &self.ctx,
                self.model.editor.scene(),
                &changed,
                self.model.toggles,
            )?;
        }
        let view_height = self.model.camera.view_height(self.model.viewport);
        self.view.sync_shape(
            &self.ctx,
            self.model.editor.scene(),
            !changed.is_empty(),
            (&self.model.shape, view_height),
            self.model.editor.selected,
        );
        let request = crate::shape::OffsetRequest::for_view(
            &self.model.shape,
            self.model.editor.selected,
            view_height,
            self.model.viewport.y,
        );
        self.model.offset.poll(
            self.model.editor.scene(),
            !changed.is_empty(),
            request,
            Instant::now(),
        );
        if let Some(s) = &mut self.stress {
            s.step(
                self.started.elapsed().as_secs_f64(),
                &self.ctx.queue,
                &self.view.gpu,
            );
            self.solve_ms.0 += s.last_solve_ms;
            self.solve_ms.1 += 1;
        }
        let Some(frame) = self.surface.acquire(&self.ctx)? else {
            return Ok(false);
        };
        let target = frame
            .texture
            .create_view(&wgpu::TextureViewDescriptor::default());
        let scale = self.surface.window.scale_factor() as f32;
        let camera = self.renderer_camera(scale);
        let mut encoder = self
            .ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("frame"),
            });
        let (panel, actions) = self.run_panel(&mut encoder);
        let settings = splinescope_gpu::adaptive::FrameSettings {
            camera,
            tolerance_px: self.model.tolerance_px as f32,
            min_count: self.view.gpu_min_count(),
        };
        let timed = self.timer.as_ref().filter(|t| t.active());
        let copied_stats = self.view.encode_tessellation(
            &self.ctx,
            &mut encoder,
            &settings,
            timed.map(|t| (t.compute_writes(), t.comb_span(), t.raster_span())),
        );
        {
            let mut pass = self
                .view
                .renderer
                .begin_timed_pass(
                    &mut encoder,
                    &target,
                    wgpu::LoadOp::Clear(self.view.gpu.background),
                    timed.map(timing::StageTimer::render_writes),
                )
                .forget_lifetime();
            self.view.renderer.draw(&mut pass, &self.view.gpu);
            self.egui.paint(&mut pass, &panel);
        }
        let timed = timed.is_some();
        if timed && let Some(t) = &self.timer {
            t.resolve(&mut encoder);
        }
        let (mut panel, actions) = (panel, actions);
        let extra = std::mem::take(&mut panel.extra);
        self.ctx
            .queue
            .submit(extra.into_iter().chain([encoder.finish()]));
        if copied_stats {
            self.view.after_submit();
        }
        if timed && let Some(t) = &mut self.timer {
            t.request();
        }
        self.surface.window.pre_present_notify();
        self.ctx.queue.present(frame);
        self.egui.finish(&panel);
        ui::apply(&mut self.model, actions);
        let title = self.model.editor.title();
        if title != self.title {
            self.surface.window.set_title(&title);
            self.title = title;
        }
        if self.model.auto_fit {
            // The panel's width is known only after it is drawn: fit to what it leaves.
            self.model.fit();
        }
        Ok(true)
    }

    /// The figures `--stats` prints.
    fn stats(&self) -> ViewStats {
        let fps = match (self.first_presented, self.last_presented) {
            (Some(a), Some(b)) if self.frames_presented > 1 && b > a => {
                (self.frames_presented - 1) as f64 / b.duration_since(a).as_secs_f64()
            }
            _ => 0.0,
        };
        let mut stage_ms = std::collections::BTreeMap::new();
        if let Some(ms) = self.timer.as_ref().and_then(timing::StageTimer::mean_ms) {
            for (name, v) in timing::STAGES.iter().zip(ms) {
                stage_ms.insert(*name, v);
            }
        }
        if self.solve_ms.1 > 0 {
            stage_ms.insert("solve", self.solve_ms.0 / f64::from(self.solve_ms.1));
        }
        ViewStats {
            frames: self.frames_presented,
            fps,
            samples_per_frame: self.view.samples_per_frame(),
            line_pieces_per_frame: self.view.pieces_per_frame(),
            stage_ms,
            tolerance_px: self.model.tolerance_px,
            capped: self.view.capped(),
            adapter: self.adapter.clone(),
        }
    }

    /// Sets the renderer's camera for this frame and returns it.
    fn renderer_camera(&self, scale: f32) -> splinescope_gpu::layout::GpuCamera {
        let camera = camera_uniform(&self.model.camera, self.model.viewport, scale);
        self.view.renderer.set_camera(&self.ctx.queue, &camera);
        camera
    }

    /// Runs the side panel for this frame (recording its uploads into `encoder`).
    fn run_panel(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
    ) -> (egui_layer::PanelFrame, ui::Actions) {
        self.fps.tick(Instant::now());
        let mut actions = ui::Actions::default();
        let camera = self.model.camera;
        let info = ui::PanelInfo {
            digest: &self.view.digest,
            adapter: &self.adapter,
            fps: self.fps.fps(),
            samples_per_frame: self.view.samples_per_frame(),
            capped: self.view.capped(),
            stage_ms: self.timer.as_ref().and_then(|t| t.last_ms),
            overlays_locked: self.model.overlays_locked,
            camera: &camera,
            solving: self.stress.as_ref().map(|s| (s.curves, s.last_solve_ms)),
            markers: &self.view.markers.markers,
            offset_status: self.model.offset.current().map(|found| match found {
                Ok(o) => format!(
                    "{} segment(s) within {:.1e} (a proven bound), {} cusp(s)",
                    o.paths.iter().map(|p| p.segments().len()).sum::<usize>(),
                    o.error,
                    o.cusps
                ),
                Err(e) => e.clone(),
            }),
        };
        let tolerance_before = self.model.tolerance_px;
        let model = &mut self.model;
        let mut panel_width = 0.0_f32;
        let size = [self.surface.config.width, self.surface.config.height];
        let (frame, pixels_per_point) =
            self.egui
                .run(&self.surface.window, &self.ctx, encoder, size, |ui| {
                    panel_width = ui::draw(ui, &info, model, &mut actions);
                });
        self.model.panel_width_px = f64::from(panel_width) * f64::from(pixels_per_point);
        let ppp = f64::from(pixels_per_point);
        self.model.ui_rects = self
            .egui
            .floating_rects()
            .into_iter()
            .map(|r| {
                (
                    DVec2::new(f64::from(r.min.x), f64::from(r.min.y)) * ppp,
                    DVec2::new(f64::from(r.max.x), f64::from(r.max.y)) * ppp,
                )
            })
            .collect();
        let t = self.model.tolerance_px;
        if !(t.is_finite() && t >= splinescope_gpu::adaptive::MIN_TOLERANCE_PX) {
            self.model.editor.message = Some(format!(
                "tolerance {t} px refused: it must be at least {} px",
                splinescope_gpu::adaptive::MIN_TOLERANCE_PX
            ));
            self.model.tolerance_px = tolerance_before;
        }
        // A panel control's drag (a slider) is one edit: commit it when the pointer lets go.
        if !self.model.is_editing() && self.egui.pointer_released() {
            self.model.editor.finish();
        }
        (frame, actions)
    }
}
