/* ms a step (best of R runs of S steps) of table1's tablecloth, or with
 * wind = 1 msocl-bench wind's flag in a 5 m/s wind, with the builder's
 * dashpots DAMP, GRID AUTO, symplectic Euler at half the stable step
 * (see dashpots.txt).
 *   cc -O2 -I LIB dashpots.c -o dashpots LIB/.libs/libmsocl.so -Wl,-rpath,LIB/.libs
 *   ./dashpots N S R DAMP [wind] */
#include <msocl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
static double now(void){struct timespec t;clock_gettime(CLOCK_MONOTONIC,&t);return t.tv_sec+1e-9*t.tv_nsec;}
int main(int argc,char**argv){
  int n=atoi(argv[1]), steps=atoi(argv[2]), rep=atoi(argv[3]); float damp=atof(argv[4]); int wind=argc>5&&atoi(argv[5]);
  msocl_runtime*rt=NULL; if(msocl_runtime_create(&rt,NULL)){puts(msocl_last_error());return 1;}
  msocl_cloth_desc d; msocl_cloth_desc_init(&d); d.nx=d.ny=n;
  if(!wind){float o[3]={-0.5f,0.05f,-0.5f},u[3]={0,0,1},v[3]={1,0,0};memcpy(d.origin,o,12);memcpy(d.u,u,12);memcpy(d.v,v,12);}
  else {d.u[0]=1;d.v[0]=0;d.v[1]=-1;d.v[2]=0;}
  d.point_mass=0.5f/(float)(n*n); d.k_stretch=50; d.k_shear=10; d.k_bend=10; d.damping=damp;
  msocl_model*m=NULL; msocl_model_cloth_grid(&m,&d);
  float top[3]={0,0,0};
  if(!wind) msocl_model_add_table(m,top,0.35f,0.3f); else {msocl_model_pin(m,0,1);msocl_model_pin(m,n-1,1);}
  msocl_model_set_viscous_damping(m,0.5f*d.point_mass);
  float dt; msocl_stable_dt(m,MSOCL_SYMPLECTIC_EULER,&dt);
  msocl_sim_options op; msocl_sim_options_init(&op); op.dt=dt*0.5f; op.tuning.layout=MSOCL_LAYOUT_GRID;
  msocl_sim*s=NULL; if(msocl_sim_create(&s,rt,m,&op)){puts(msocl_last_error());return 1;}
  if(wind){msocl_wind w; msocl_wind_init(&w); w.velocity[2]=5; w.lift=0.5f; if(msocl_sim_set_wind(s,&w)){puts(msocl_last_error());return 1;}}
  msocl_sim_step(s,2);
  double best=1e9; float *p=malloc(12*(size_t)n*n);
  for(int r=0;r<rep;r++){double t=now(); msocl_sim_step(s,steps); msocl_sim_read_positions(s,p); t=now()-t; if(t<best)best=t;}
  printf("n=%d damp=%g wind=%d: %.3f ms/step  (p0.y %g)\n",n,damp,wind,1e3*best/steps,p[1]);
  return 0;}
