// Writes a plant's state into the registers of its dialect, by the core map's keys.
#pragma once

#include "plant/plant_model.h"
#include "plant/register_image.h"

namespace pvtap::sim {

void fill_registers(const PlantModel& plant, RegisterImage& image, Dialect dialect);

}  // namespace pvtap::sim
