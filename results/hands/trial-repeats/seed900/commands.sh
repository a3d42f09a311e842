#!/bin/sh
# the commands of scripts/hands_trial.py, in the order they ran
graspmix_cli acquire --object random_urdfs/014/014.urdf --views 4 --noise --seed 900 --out runs/trial-seed900/clouds/00_014.pcd
graspmix_cli synthesize --model data/models/box_wsg50_gmm.json --cloud runs/trial-seed900/clouds/00_014.pcd --out runs/trial-seed900/wsg50/00_014.json
graspmix_cli synthesize --model models/panda/model.json --cloud runs/trial-seed900/clouds/00_014.pcd --out runs/trial-seed900/panda/00_014.json
graspmix_cli synthesize --model models/xarm/model.json --cloud runs/trial-seed900/clouds/00_014.pcd --out runs/trial-seed900/xarm/00_014.json
graspmix_cli synthesize --model models/pr2/model.json --cloud runs/trial-seed900/clouds/00_014.pcd --out runs/trial-seed900/pr2/00_014.json
graspmix_cli synthesize --model models/three_finger/model.json --cloud runs/trial-seed900/clouds/00_014.pcd --out runs/trial-seed900/three_finger/00_014.json
graspmix_cli acquire --object random_urdfs/029/029.urdf --views 4 --noise --seed 901 --out runs/trial-seed900/clouds/01_029.pcd
graspmix_cli synthesize --model data/models/box_wsg50_gmm.json --cloud runs/trial-seed900/clouds/01_029.pcd --out runs/trial-seed900/wsg50/01_029.json
graspmix_cli synthesize --model models/panda/model.json --cloud runs/trial-seed900/clouds/01_029.pcd --out runs/trial-seed900/panda/01_029.json
graspmix_cli synthesize --model models/xarm/model.json --cloud runs/trial-seed900/clouds/01_029.pcd --out runs/trial-seed900/xarm/01_029.json
graspmix_cli synthesize --model models/pr2/model.json --cloud runs/trial-seed900/clouds/01_029.pcd --out runs/trial-seed900/pr2/01_029.json
graspmix_cli synthesize --model models/three_finger/model.json --cloud runs/trial-seed900/clouds/01_029.pcd --out runs/trial-seed900/three_finger/01_029.json
graspmix_cli acquire --object random_urdfs/030/030.urdf --views 4 --noise --seed 902 --out runs/trial-seed900/clouds/02_030.pcd
graspmix_cli synthesize --model data/models/box_wsg50_gmm.json --cloud runs/trial-seed900/clouds/02_030.pcd --out runs/trial-seed900/wsg50/02_030.json
graspmix_cli synthesize --model models/panda/model.json --cloud runs/trial-seed900/clouds/02_030.pcd --out runs/trial-seed900/panda/02_030.json
graspmix_cli synthesize --model models/xarm/model.json --cloud runs/trial-seed900/clouds/02_030.pcd --out runs/trial-seed900/xarm/02_030.json
graspmix_cli synthesize --model models/pr2/model.json --cloud runs/trial-seed900/clouds/02_030.pcd --out runs/trial-seed900/pr2/02_030.json
graspmix_cli synthesize --model models/three_finger/model.json --cloud runs/trial-seed900/clouds/02_030.pcd --out runs/trial-seed900/three_finger/02_030.json
graspmix_cli acquire --object random_urdfs/033/033.urdf --views 4 --noise --seed 903 --out runs/trial-seed900/clouds/03_033.pcd
graspmix_cli synthesize --model data/models/box_wsg50_gmm.json --cloud runs/trial-seed900/clouds/03_033.pcd --out runs/trial-seed900/wsg50/03_033.json
graspmix_cli synthesize --model models/panda/model.json --cloud runs/trial-seed900/clouds/03_033.pcd --out runs/trial-seed900/panda/03_033.json
graspmix_cli synthesize --model models/xarm/model.json --cloud runs/trial-seed900/clouds/03_033.pcd --out runs/trial-seed900/xarm/03_033.json
graspmix_cli synthesize --model models/pr2/model.json --cloud runs/trial-seed900/clouds/03_033.pcd --out runs/trial-seed900/pr2/03_033.json
graspmix_cli synthesize --model models/three_finger/model.json --cloud runs/trial-seed900/clouds/03_033.pcd --out runs/trial-seed900/three_finger/03_033.json
graspmix_cli acquire --object random_urdfs/055/055.urdf --views 4 --noise --seed 904 --out runs/trial-seed900/clouds/04_055.pcd
graspmix_cli synthesize --model data/models/box_wsg50_gmm.json --cloud runs/trial-seed900/clouds/04_055.pcd --out runs/trial-seed900/wsg50/04_055.json
graspmix_cli synthesize --model models/panda/model.json --cloud runs/trial-seed900/clouds/04_055.pcd --out runs/trial-seed900/panda/04_055.json
graspmix_cli synthesize --model models/xarm/model.json --cloud runs/trial-seed900/clouds/04_055.pcd --out runs/trial-seed900/xarm/04_055.json
graspmix_cli synthesize --model models/pr2/model.json --cloud runs/trial-seed900/clouds/04_055.pcd --out runs/trial-seed900/pr2/04_055.json
graspmix_cli synthesize --model models/three_finger/model.json --cloud runs/trial-seed900/clouds/04_055.pcd --out runs/trial-seed900/three_finger/04_055.json
graspmix_cli acquire --object random_urdfs/056/056.urdf --views 4 --noise --seed 905 --out runs/trial-seed900/clouds/05_056.pcd
graspmix_cli synthesize --model data/models/box_wsg50_gmm.json --cloud runs/trial-seed900/clouds/05_056.pcd --out runs/trial-seed900/wsg50/05_056.json
graspmix_cli synthesize --model models/panda/model.json --cloud runs/trial-seed900/clouds/05_056.pcd --out runs/trial-seed900/panda/05_056.json
graspmix_cli synthesize --model models/xarm/model.json --cloud runs/trial-seed900/clouds/05_056.pcd --out runs/trial-seed900/xarm/05_056.json
graspmix_cli synthesize --model models/pr2/model.json --cloud runs/trial-seed900/clouds/05_056.pcd --out runs/trial-seed900/pr2/05_056.json
graspmix_cli synthesize --model models/three_finger/model.json --cloud runs/trial-seed900/clouds/05_056.pcd --out runs/trial-seed900/three_finger/05_056.json
graspmix_cli acquire --object random_urdfs/065/065.urdf --views 4 --noise --seed 906 --out runs/trial-seed900/clouds/06_065.pcd
graspmix_cli synthesize --model data/models/box_wsg50_gmm.json --cloud runs/trial-seed900/clouds/06_065.pcd --out runs/trial-seed900/wsg50/06_065.json
graspmix_cli synthesize --model models/panda/model.json --cloud runs/trial-seed900/clouds/06_065.pcd --out runs/trial-seed900/panda/06_065.json
graspmix_cli synthesize --model models/xarm/model.json --cloud runs/trial-seed900/clouds/06_065.pcd --out runs/trial-seed900/xarm/06_065.json
graspmix_cli synthesize --model models/pr2/model.json --cloud runs/trial-seed900/clouds/06_065.pcd --out runs/trial-seed900/pr2/06_065.json
graspmix_cli synthesize --model models/three_finger/model.json --cloud runs/trial-seed900/clouds/06_065.pcd --out runs/trial-seed900/three_finger/06_065.json
graspmix_cli acquire --object random_urdfs/068/068.urdf --views 4 --noise --seed 907 --out runs/trial-seed900/clouds/07_068.pcd
graspmix_cli synthesize --model data/models/box_wsg50_gmm.json --cloud runs/trial-seed900/clouds/07_068.pcd --out runs/trial-seed900/wsg50/07_068.json
graspmix_cli synthesize --model models/panda/model.json --cloud runs/trial-seed900/clouds/07_068.pcd --out runs/trial-seed900/panda/07_068.json
graspmix_cli synthesize --model models/xarm/model.json --cloud runs/trial-seed900/clouds/07_068.pcd --out runs/trial-seed900/xarm/07_068.json
graspmix_cli synthesize --model models/pr2/model.json --cloud runs/trial-seed900/clouds/07_068.pcd --out runs/trial-seed900/pr2/07_068.json
graspmix_cli synthesize --model models/three_finger/model.json --cloud runs/trial-seed900/clouds/07_068.pcd --out runs/trial-seed900/three_finger/07_068.json
graspmix_cli acquire --object random_urdfs/083/083.urdf --views 4 --noise --seed 908 --out runs/trial-seed900/clouds/08_083.pcd
graspmix_cli synthesize --model data/models/box_wsg50_gmm.json --cloud runs/trial-seed900/clouds/08_083.pcd --out runs/trial-seed900/wsg50/08_083.json
graspmix_cli synthesize --model models/panda/model.json --cloud runs/trial-seed900/clouds/08_083.pcd --out runs/trial-seed900/panda/08_083.json
graspmix_cli synthesize --model models/xarm/model.json --cloud runs/trial-seed900/clouds/08_083.pcd --out runs/trial-seed900/xarm/08_083.json
graspmix_cli synthesize --model models/pr2/model.json --cloud runs/trial-seed900/clouds/08_083.pcd --out runs/trial-seed900/pr2/08_083.json
graspmix_cli synthesize --model models/three_finger/model.json --cloud runs/trial-seed900/clouds/08_083.pcd --out runs/trial-seed900/three_finger/08_083.json
graspmix_cli acquire --object random_urdfs/091/091.urdf --views 4 --noise --seed 909 --out runs/trial-seed900/clouds/09_091.pcd
graspmix_cli synthesize --model data/models/box_wsg50_gmm.json --cloud runs/trial-seed900/clouds/09_091.pcd --out runs/trial-seed900/wsg50/09_091.json
graspmix_cli synthesize --model models/panda/model.json --cloud runs/trial-seed900/clouds/09_091.pcd --out runs/trial-seed900/panda/09_091.json
graspmix_cli synthesize --model models/xarm/model.json --cloud runs/trial-seed900/clouds/09_091.pcd --out runs/trial-seed900/xarm/09_091.json
graspmix_cli synthesize --model models/pr2/model.json --cloud runs/trial-seed900/clouds/09_091.pcd --out runs/trial-seed900/pr2/09_091.json
graspmix_cli synthesize --model models/three_finger/model.json --cloud runs/trial-seed900/clouds/09_091.pcd --out runs/trial-seed900/three_finger/09_091.json
graspmix_cli acquire --object random_urdfs/098/098.urdf --views 4 --noise --seed 910 --out runs/trial-seed900/clouds/10_098.pcd
graspmix_cli synthesize --model data/models/box_wsg50_gmm.json --cloud runs/trial-seed900/clouds/10_098.pcd --out runs/trial-seed900/wsg50/10_098.json
graspmix_cli synthesize --model models/panda/model.json --cloud runs/trial-seed900/clouds/10_098.pcd --out runs/trial-seed900/panda/10_098.json
graspmix_cli synthesize --model models/xarm/model.json --cloud runs/trial-seed900/clouds/10_098.pcd --out runs/trial-seed900/xarm/10_098.json
graspmix_cli synthesize --model models/pr2/model.json --cloud runs/trial-seed900/clouds/10_098.pcd --out runs/trial-seed900/pr2/10_098.json
graspmix_cli synthesize --model models/three_finger/model.json --cloud runs/trial-seed900/clouds/10_098.pcd --out runs/trial-seed900/three_finger/10_098.json
graspmix_cli acquire --object random_urdfs/113/113.urdf --views 4 --noise --seed 911 --out runs/trial-seed900/clouds/11_113.pcd
graspmix_cli synthesize --model data/models/box_wsg50_gmm.json --cloud runs/trial-seed900/clouds/11_113.pcd --out runs/trial-seed900/wsg50/11_113.json
graspmix_cli synthesize --model models/panda/model.json --cloud runs/trial-seed900/clouds/11_113.pcd --out runs/trial-seed900/panda/11_113.json
graspmix_cli synthesize --model models/xarm/model.json --cloud runs/trial-seed900/clouds/11_113.pcd --out runs/trial-seed900/xarm/11_113.json
graspmix_cli synthesize --model models/pr2/model.json --cloud runs/trial-seed900/clouds/11_113.pcd --out runs/trial-seed900/pr2/11_113.json
graspmix_cli synthesize --model models/three_finger/model.json --cloud runs/trial-seed900/clouds/11_113.pcd --out runs/trial-seed900/three_finger/11_113.json
