#pragma once
/// @file eco.hpp
/// Umbrella header of the ECO core library.

#include <eco/config.hpp>
#include <eco/ego_octree.hpp>
#include <eco/process_heap.hpp>
#include <eco/types.hpp>
#include <eco/version.hpp>
