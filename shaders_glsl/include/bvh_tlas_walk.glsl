// bvh_tlas_walk.glsl: the binary TLAS walk, written once for every BLAS layout. Included (without a guard, on
// purpose) by include/bvh_traverse.glsl for binary BLASes and by include/bvh_traverse_wide.glsl for 8-wide ones;
// the includer defines BVH_TLAS_WALK (the function's name) and BVH_TLAS_BLAS_WALK (the BLAS walk it calls per
// instance; same parameters as bvhTraverseBlas), and this file undefines both. GLSL has no function pointers, so
// the preprocessor picks the BLAS walk. Order, tie rule and the stack-overflow flag are bvh::closestHit's (TLAS).
bool BVH_TLAS_WALK(GpuTlasDesc tlas, vec3 origin, vec3 direction, float tMin, float tMax, bool anyHit,
                   inout BvhBest best) {
    BvhPreparedRay world = bvhPrepareRay(origin, direction, tMin, tMax);
    if (!world.valid) return false;
    BvhTlasNodeRef nodes = BvhTlasNodeRef(tlas.nodes);
    BvhUintRef order = BvhUintRef(tlas.instanceOrder);
    BvhInstanceRef instances = BvhInstanceRef(tlas.instances);
    BvhBlasDescRef blases = BvhBlasDescRef(tlas.blases);
    GpuTlasNode root = nodes.n[kBvhRootNode];
    float tRoot;
    if (!bvhIntersectBox(world, root.min, root.max, bvhBoxLimit(best.t), tRoot)) return false;
    uint stackPair[BVH_TLAS_STACK_SIZE];
    float stackT[BVH_TLAS_STACK_SIZE];
    uint size = 0u;
    uint pair = root.instanceStartOrChild;
    for (;;) {
        GpuTlasNode left = nodes.n[pair];
        GpuTlasNode right = nodes.n[pair + 1u];
        float limit = bvhBoxLimit(best.t);
        float tLeft, tRight;
        bool hitLeft = bvhIntersectBox(world, left.min, left.max, limit, tLeft);
        bool hitRight = bvhIntersectBox(world, right.min, right.max, limit, tRight);
        bool leafLeft = hitLeft && left.instanceCount > 0u;
        bool leafRight = hitRight && right.instanceCount > 0u;
        if (leafLeft || leafRight) {
            uint start = leafLeft ? left.instanceStartOrChild : right.instanceStartOrChild;
            uint end = leafRight ? right.instanceStartOrChild + right.instanceCount
                                 : left.instanceStartOrChild + left.instanceCount;
            for (uint k = start; k < end; ++k) {
                uint id = order.u[k];
                GpuBvhInstance inst = instances.i[id];
                vec3 localOrigin = bvhTransform(inst.worldToObject[0], inst.worldToObject[1], inst.worldToObject[2],
                                                inst.worldToObject[3], origin, 1.0);
                vec3 localDirection = bvhTransform(inst.worldToObject[0], inst.worldToObject[1],
                                                   inst.worldToObject[2], inst.worldToObject[3], direction, 0.0);
                BvhPreparedRay local = bvhPrepareRay(localOrigin, localDirection, tMin, tMax);
                if (BVH_TLAS_BLAS_WALK(blases.d[inst.blasIndex], local, id, anyHit, best)) return true;
            }
        }
        bool innerLeft = hitLeft && left.instanceCount == 0u;
        bool innerRight = hitRight && right.instanceCount == 0u;
        if (innerLeft && innerRight) {
            bool leftFirst = tLeft <= tRight;
            if (size < uint(BVH_TLAS_STACK_SIZE)) {
                stackPair[size] = leftFirst ? right.instanceStartOrChild : left.instanceStartOrChild;
                stackT[size] = leftFirst ? tRight : tLeft;
                ++size;
            } else {
                best.flags |= kBvhHitFlagStackOverflow;
            }
            pair = leftFirst ? left.instanceStartOrChild : right.instanceStartOrChild;
            continue;
        }
        if (innerLeft || innerRight) {
            pair = innerLeft ? left.instanceStartOrChild : right.instanceStartOrChild;
            continue;
        }
        bool found = false;
        while (size > 0u) {
            --size;
            if (stackT[size] <= bvhBoxLimit(best.t)) {
                pair = stackPair[size];
                found = true;
                break;
            }
        }
        if (!found) return false;
    }
    return false;
}

#undef BVH_TLAS_WALK
#undef BVH_TLAS_BLAS_WALK
