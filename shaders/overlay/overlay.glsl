// The overlay's push constants (generated as `OverlayPush`).
layout(push_constant) uniform Overlay {
    // The screen's size in egui points (pixels divided by pixels-per-point).
    vec2 screen_points;
} overlay;
