#!/usr/bin/python3
"""A GSL inverter played by pymodbus (Debian's python3-pymodbus 3.0): a Modbus RTU server on a
serial device holding GSL register IDs at their decimal wire addresses (ID 1050 = 0x041A).
Writes the words it holds as JSON before it starts serving, for the ground truth.

usage: gsl_server.py DEVICE STATION TRUTH_JSON
"""
import json
import sys

from pymodbus.datastore import (ModbusSequentialDataBlock, ModbusServerContext,
                                ModbusSlaveContext)
from pymodbus.server import StartSerialServer
from pymodbus.transaction import ModbusRtuFramer


def text_words(text):
    padded = text.ljust(10)
    return [ord(padded[i]) << 8 | ord(padded[i + 1]) for i in range(0, 10, 2)]


def gsl_registers():
    """ID -> word: a 3-phase plant at noon, model and maker names, one alarm bit."""
    held = {}
    for i, w in enumerate(text_words("GSL000500K") + text_words("KSTARSOLAR")):
        held[1000 + i] = w
    held.update({1030: 0x0004, 1031: 0, 1032: 0, 1033: 0x0830})
    measured = [4012, 4008, 4021, 712, 709, 715, 5001, 99, 98, 99, 162, 160, 163, 3, 2, 4,
                6120, 84, 51, 187, 968, 42, 413, 2024, 6, 21, 6, 12, 30, 2024, 6, 20, 19, 45,
                3, 75, 3, 52910, 485, 9, 525, 0, 100, 99, 1, 4431]
    for i, w in enumerate(measured):
        held[1050 + i] = w
    return held


def main():
    device, station, truth_path = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    held = gsl_registers()
    words = [0] * 2100
    for address, value in held.items():
        words[address] = value
    # zero_mode: the request's address is the block index, with no +1 of Modbus references.
    slave = ModbusSlaveContext(hr=ModbusSequentialDataBlock(0, words), zero_mode=True)
    context = ModbusServerContext(slaves={station: slave}, single=False)
    with open(truth_path, "w", encoding="utf-8") as f:
        json.dump({"station": station, "holding_registers":
                   {str(a): v for a, v in sorted(held.items())}}, f, indent=1)
    StartSerialServer(context=context, framer=ModbusRtuFramer, port=device, baudrate=9600,
                      bytesize=8, parity="N", stopbits=1)


if __name__ == "__main__":
    main()
