//! The egui layer: window input for the panel, running the panel's UI, and painting it
//! over the scene in the same render pass.

use winit::event::WindowEvent;
use winit::window::Window;

use splinescope_gpu::GpuContext;

/// egui's state for one window.
pub(crate) struct EguiLayer {
    ctx: egui::Context,
    state: egui_winit::State,
    renderer: egui_wgpu::Renderer,
}

/// A panel frame, tessellated and uploaded, ready to paint.
pub(crate) struct PanelFrame {
    jobs: Vec<egui::ClippedPrimitive>,
    screen: egui_wgpu::ScreenDescriptor,
    free: Vec<egui::TextureId>,
    /// Command buffers egui's callbacks need submitted before the frame's.
    pub extra: Vec<wgpu::CommandBuffer>,
}

impl EguiLayer {
    pub fn new(window: &Window, ctx: &GpuContext, format: wgpu::TextureFormat) -> EguiLayer {
        let egui_ctx = egui::Context::default();
        let state = egui_winit::State::new(
            egui_ctx.clone(),
            egui::ViewportId::ROOT,
            window,
            Some(window.scale_factor() as f32),
            None,
            Some(ctx.device.limits().max_texture_dimension_2d as usize),
        );
        let renderer =
            egui_wgpu::Renderer::new(&ctx.device, format, egui_wgpu::RendererOptions::default());
        EguiLayer {
            ctx: egui_ctx,
            state,
            renderer,
        }
    }

    /// Gives a window event to egui; whether egui took it (the scene must not).
    pub fn on_window_event(&mut self, window: &Window, event: &WindowEvent) -> bool {
        self.state.on_window_event(window, event).consumed
    }

    /// The rectangles of egui's floating layers shown this frame (menus, popups, windows;
    /// not the background, where the panel and the canvas are), in points.
    pub fn floating_rects(&self) -> Vec<egui::Rect> {
        self.ctx.memory(|m| {
            m.areas()
                .visible_layer_ids()
                .into_iter()
                .filter(|layer| layer.order != egui::Order::Background)
                .filter_map(|layer| m.area_rect(layer.id))
                .collect()
        })
    }

    /// Whether the pointer was released this frame (a slider drag ends an edit).
    pub fn pointer_released(&self) -> bool {
        self.ctx.input(|i| i.pointer.any_released())
    }

    /// Runs `ui` for this frame and uploads what it drew into `encoder`'s frame. Returns
    /// the frame to paint and the pixels per point.
    pub fn run(
        &mut self,
        window: &Window,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        size_in_pixels: [u32; 2],
        ui: impl FnMut(&mut egui::Ui),
    ) -> (PanelFrame, f32) {
        let raw = self.state.take_egui_input(window);
        let output = self.ctx.run_ui(raw, ui);
        self.state
            .handle_platform_output(window, output.platform_output);
        let jobs = self.ctx.tessellate(output.shapes, output.pixels_per_point);
        for (id, deltas) in &output.textures_delta.set {
            for delta in deltas {
                self.renderer
                    .update_texture(&gpu.device, &gpu.queue, *id, delta);
            }
        }
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels,
            pixels_per_point: output.pixels_per_point,
        };
        let extra = self
            .renderer
            .update_buffers(&gpu.device, &gpu.queue, encoder, &jobs, &screen);
        (
            PanelFrame {
                jobs,
                screen,
                free: output.textures_delta.free.iter().copied().collect(),
                extra,
            },
            output.pixels_per_point,
        )
    }

    /// Paints the panel into `pass`.
    pub fn paint(&self, pass: &mut wgpu::RenderPass<'static>, frame: &PanelFrame) {
        self.renderer.render(pass, &frame.jobs, &frame.screen);
    }

    /// Frees the textures the frame no longer needs (after submission).
    pub fn finish(&mut self, frame: &PanelFrame) {
        for id in &frame.free {
            self.renderer.free_texture(id);
        }
    }
}
