/* Steps per second of one simulation stepped in calls of 1, 10, 100 and
 * all steps, in float4 and in planes: the cost of a call (see calls.txt).
 *   cc -O2 -I LIB calls.c -o calls LIB/.libs/libmsocl.so -Wl,-rpath,LIB/.libs -lm
 *   ./calls N STEPS [cloth]    (an N^3 lattice, or an N x N cloth) */
#include <msocl.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
static double now(void){struct timespec t;clock_gettime(CLOCK_MONOTONIC,&t);return t.tv_sec+1e-9*t.tv_nsec;}
int main(int argc,char**argv){
  int n=atoi(argv[1]), total=atoi(argv[2]);
  msocl_model*m;
  if (argc>3) { msocl_cloth_desc d; msocl_cloth_desc_init(&d); d.nx=d.ny=n; if(msocl_model_cloth_grid(&m,&d)) return 1; }
  else { msocl_lattice_desc d; msocl_lattice_desc_init(&d); d.nx=d.ny=d.nz=n; if(msocl_model_lattice(&m,&d)) return 1; }
  const float up[3]={0,1,0}; msocl_model_add_plane(m,up,0,0.5f);
  msocl_runtime*rt; if(msocl_runtime_create(&rt,NULL)) return 1;
  for(int pl=0;pl<2;pl++){
    msocl_sim_options o; msocl_sim_options_init(&o); o.dt=1e-4f; o.planes=pl;
    msocl_sim*s; if(msocl_sim_create(&s,rt,m,&o)){puts(msocl_last_error());return 1;}
    msocl_sim_step(s,5);
    int calls[]={1,10,100,total};
    for(int c=0;c<4;c++){
      double t0=now(); for(int k=0;k<total/calls[c];k++) msocl_sim_step(s,calls[c]); double t=now()-t0;
      printf("n %d planes %d: calls of %4d: %8.1f steps/s\n",n,pl,calls[c],total/t);
    }
    msocl_sim_destroy(s);
  }
  return 0;
}
