// What a stream element's ray is for; kept in the origin surface's w and
// mirrored by accel/ray_stream_layout.h.
const float RAY_NONE = 0.0;     // no ray: the element is finished
const float RAY_NEAREST = 1.0;  // camera or reflection ray: find the nearest hit
const float RAY_SHADOW = 2.0;   // shadow ray: any hit before tMax occludes the light
