// The eye ray through a fragment and the distance along it to the first surface, from the
// frame's camera and depth buffer. Needs frame_uniforms.h.

// Unit direction of the eye ray through window position `fragment` (gl_FragCoord.xy).
vec3 eye_ray_direction(vec2 fragment) {
    vec2 ndc = 2.0 * fragment / frame.display.yz - 1.0;
    vec4 far_point = frame.inverse_view_projection * vec4(ndc, 1.0, 1.0);
    return normalize(far_point.xyz / far_point.w - frame.camera_position.xyz);
}

// Distance from the camera to the surface seen at `fragment`, +inf where nothing was drawn.
float surface_distance(sampler2D depth_buffer, vec2 fragment) {
    float depth = texelFetch(depth_buffer, ivec2(fragment), 0).r;
    if (depth >= 1.0) return 1.0 / 0.0;
    vec2 ndc = 2.0 * fragment / frame.display.yz - 1.0;
    vec4 surface = frame.inverse_view_projection * vec4(ndc, 2.0 * depth - 1.0, 1.0);
    return length(surface.xyz / surface.w - frame.camera_position.xyz);
}

// Distance from the camera to the far plane along the eye ray through `fragment`.
float far_plane_distance(vec2 fragment) {
    vec2 ndc = 2.0 * fragment / frame.display.yz - 1.0;
    vec4 far_point = frame.inverse_view_projection * vec4(ndc, 1.0, 1.0);
    return length(far_point.xyz / far_point.w - frame.camera_position.xyz);
}

// Where the eye ray through `fragment` ends, in every method and the reference: at the surface it
// sees, or at the far plane where it sees none (docs/design.md §1).
float eye_ray_end(sampler2D depth_buffer, vec2 fragment) {
    return min(surface_distance(depth_buffer, fragment), far_plane_distance(fragment));
}
