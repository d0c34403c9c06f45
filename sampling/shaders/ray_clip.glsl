// Moschos algorithm 4: the trace [0, trace_end] clipped to the convex influence volume given by
// its outward planes (xyz normal, w offset), GLSL twin of sampling/ray_clip.cpp. Returns
// (start, end, case) with case 0..5 for A..F; cases A and F sample nothing.
vec3 clip_trace(vec3 origin, vec3 direction, float trace_end, vec4 planes[6]) {
    float enter = -1.0 / 0.0, leave = 1.0 / 0.0;
    for (int i = 0; i < 6; ++i) {
        float distance = dot(planes[i].xyz, origin) + planes[i].w;
        float rate = dot(planes[i].xyz, direction);
        if (rate == 0.0) {
            if (distance > 0.0) return vec3(0.0, 0.0, 0.0);
            continue;
        }
        float t = -distance / rate;
        if (rate < 0.0) enter = max(enter, t); else leave = min(leave, t);
    }
    if (!(leave > enter) || leave <= 0.0) return vec3(0.0, 0.0, 0.0);     // A
    if (enter <= 0.0) {
        return leave < trace_end ? vec3(0.0, leave, 1.0)                  // B
                                 : vec3(0.0, trace_end, 2.0);             // C
    }
    if (leave < trace_end) return vec3(enter, leave, 3.0);                // D
    if (enter < trace_end) return vec3(enter, trace_end, 4.0);            // E
    return vec3(0.0, 0.0, 5.0);                                           // F
}
