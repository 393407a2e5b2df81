/* Private: the springs of a triangle mesh, found by sorting its edges. */
#ifndef MSOCL_MESH_EDGES_H
#define MSOCL_MESH_EDGES_H

/* Writes to *ij (malloc'd, 2 ints a spring, free() it) first the mesh's
 * unique undirected edges as (i < j) pairs in increasing order, *nedges of
 * them; then, if `bends`, one pair per edge shared by exactly two triangles
 * joining their two opposite corners, *nbends of them, each once and only
 * when they are distinct and not already joined by an edge. O(E log E). */
int msocl__mesh_springs(int nt, const int *tri, int bends, int **ij,
                        int *nedges, int *nbends);

#endif /* MSOCL_MESH_EDGES_H */
