"""Write preisach_record.csv beside this script: the synthetic record used by identify_and_predict.

The record is the output of a known non-uniform Preisach model driven through major and minor
loops, plus Gaussian noise (see exudyn_atcm.model.reference_record; the CSV header repeats it).
Run: python cases/data/make_preisach_record.py
"""

from pathlib import Path

from exudyn_atcm.model import write_reference_record

if __name__ == "__main__":
    print(write_reference_record(Path(__file__).with_name("preisach_record.csv")))
