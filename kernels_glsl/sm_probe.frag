// Which streaming multiprocessors run a pass (issue 38): every element adds
// itself to its SM's count (GL_NV_shader_thread_group's gl_SMIDNV), so a
// fragment pass and the same kernel in the compute stage each leave the SMs
// their stage could use. Run by build/tests/measure/measure_sm_probe.
#extension GL_NV_shader_thread_group : require

layout(std430, binding = 0) buffer SmInvocations { uint invocations[]; };  // per SM id

layout(location = 0) out vec4 outSm;

void main() {
  atomicAdd(invocations[gl_SMIDNV], 1u);
  outSm = vec4(float(gl_SMIDNV), float(gl_WarpIDNV), float(gl_SMCountNV), 0.0);
}
