"""The process plumbing every solver and command shares (no physics, no units): BLAS on one
thread, helpers forked onto the second core, the memory budget, deadlines, helpers that die
with their parent, the allocator's freed memory, and the start-up import hook."""
