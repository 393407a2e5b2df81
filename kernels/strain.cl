/* Strain limiting: keeping springs from stretching past (1 + limit) times
 * their rest length. Both run as Jacobi sweeps: each point gathers the
 * corrections its springs ask of it (a spring to a pinned point asks the
 * free end for all of it, otherwise each end takes half) and moves by
 * their average, each weighted by its own size. Their plain sum
 * overshoots wherever several springs pull one way (a structural and a
 * bend spring along a row), and the overshoot, taken up by the
 * velocities, grew without bound: with one to three sweeps a step at half
 * the stable step, or ten near it (tests/check_strain). An average never
 * moves a point further than its largest ask; weighting by size keeps the
 * move continuous as a spring crosses the limit (a plain average over the
 * springs asking halves a correction when a second spring just starts
 * to), and lets the largest ask lead. Needs common.cl before it. */

/* Vassilev, Spanlang & Chrysanthou 2001: between the velocity and the
 * position pass, limit the rate at which each spring grows so that after
 * the step it is no longer than the limit: the relative velocity along the
 * spring may be at most ((1 + limit) r - l) / dt. The collision response
 * (without friction, which the velocity pass applied) is applied again to
 * the corrected velocity. */
__kernel void msocl_strain_velocity(MSOCL_CONN, __global const float4 *pos,
                                    __global const float4 *vel,
                                    __global float4 *vel_out, float limit,
                                    float dt, __constant float4 *col,
                                    int ncol, int n)
{
  int i = get_global_id(0);
  if (i >= n)
    return;
  float4 p4 = pos[i];
  if (MSOCL_PINNED(p4)) {
    vel_out[i] = (float4)(0.0f);
    return;
  }
  float3 p = p4.xyz, v = vel[i].xyz, dv = (float3)(0.0f);
  float weight = 0.0f;
  for (int s = 0; s < MSOCL_MAX_SLOTS; s++) {
    int j;
    float rest, k, c;
    if (!msocl_slot(MSOCL_CONN_ARGS, i, s, n, &j, &rest, &k, &c))
      break;
    float4 q4 = pos[j];
    float3 d = q4.xyz - p;
    float len = MSOCL_SQRT(dot(d, d));
    if (!(len > 0.0f))
      continue;
    float allowed = MSOCL_DIV((1.0f + limit) * rest - len, dt);
    float excess = MSOCL_DIV(dot(vel[j].xyz - v, d), len) - allowed;
    if (excess > 0.0f) {
      float ask = (MSOCL_PINNED(q4) ? 1.0f : 0.5f) * excess;
      dv += (ask * MSOCL_DIV(ask, len)) * d;
      weight += ask;
    }
  }
  if (weight > 0.0f)
    dv = MSOCL_DIV(dv, weight);
  vel_out[i] = (float4)(msocl_collide(p, v + dv, dt, col, ncol, 0.0f), 0.0f);
}

/* Provot 1995: after the step, move the end points of every spring longer
 * than the limit towards each other until it is at the limit (then
 * msocl_strain_commit). */
__kernel void msocl_strain_position(MSOCL_CONN, __global const float4 *pos,
                                    __global float4 *pos_out, float limit,
                                    int n)
{
  int i = get_global_id(0);
  if (i >= n)
    return;
  float4 p4 = pos[i];
  if (MSOCL_PINNED(p4)) {
    pos_out[i] = p4;
    return;
  }
  float3 p = p4.xyz, dp = (float3)(0.0f);
  float weight = 0.0f;
  for (int s = 0; s < MSOCL_MAX_SLOTS; s++) {
    int j;
    float rest, k, c;
    if (!msocl_slot(MSOCL_CONN_ARGS, i, s, n, &j, &rest, &k, &c))
      break;
    float4 q4 = pos[j];
    float3 d = q4.xyz - p;
    float len = MSOCL_SQRT(dot(d, d));
    float over = len - (1.0f + limit) * rest;
    if (over > 0.0f) {
      float ask = (MSOCL_PINNED(q4) ? 1.0f : 0.5f) * over;
      dp += (ask * MSOCL_DIV(ask, len)) * d;
      weight += ask;
    }
  }
  if (weight > 0.0f)
    dp = MSOCL_DIV(dp, weight);
  pos_out[i] = (float4)(p + dp, p4.w);
}

/* Ends Provot's correction: the velocity takes up the distance the
 * correction moved the point (v += dp / dt), or else it would keep the
 * stretching speed the positions no longer show and grow without bound. */
__kernel void msocl_strain_commit(__global float4 *pos,
                                  __global const float4 *corrected,
                                  __global float4 *vel, float dt, int n)
{
  int i = get_global_id(0);
  if (i >= n)
    return;
  float4 c = corrected[i];
  vel[i] = (float4)(vel[i].xyz + MSOCL_DIV(c.xyz - pos[i].xyz, dt), 0.0f);
  pos[i] = c;
}
